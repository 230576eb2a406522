#pragma once
// B-rep parts written by OpenCASCADE as STEP or IGES files (by the file's extension), for
// the tests of CAD import and for scenes/parts/ (tests/tools/make_cad_parts.cpp).
#include <string>
#include <vector>

#include "io/cad_load.h"
#include "snapfit/scene.h"

namespace snapfit::test {

// The solid that mesh/procedural makes from `spec` ("peg" or "hole_block", the same
// parameters, segments ignored), with exact circles and cones instead of N-gon prisms.
// `unit` is the file's length unit ("MM", "M", "INCH"; the coordinates stay in
// millimetres), `solid_name` the name the file gives the solid.
void write_cad_part(const std::string& file, const ProceduralPartSpec& spec, const std::string& unit = "MM",
                    const std::string& solid_name = "");

// Axis-aligned boxes (millimetres) in one STEP file, one solid each, with the given names
// ("" for none), in one product named `product`.
struct NamedBox {
  std::string name;
  double min[3];
  double max[3];
};
void write_cad_boxes(const std::string& file, const std::vector<NamedBox>& boxes, const std::string& product = "");

// One box placed twice (the second shifted by `shift` mm along x), as an assembly holds
// two instances of one part: the product is named `box.name`, the solids are not.
void write_cad_instances(const std::string& file, const NamedBox& box, double shift);

// Import options that tessellate within `deflection` (the file's length unit).
inline CadImportOptions with_deflection(double deflection) {
  CadImportOptions o;
  o.linear_deflection = deflection;
  return o;
}

}  // namespace snapfit::test
