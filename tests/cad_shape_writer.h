#pragma once
// Writes an OpenCASCADE shape (millimetres) as a STEP file in millimetres, in a child
// process (tests/cad_fixtures.cpp says why), its solids named in file order.
#include <TopoDS_Shape.hxx>
#include <string>

namespace snapfit::test {

void write_cad_shape(const std::string& file, const TopoDS_Shape& mm_shape, const std::string& solid_name);

}  // namespace snapfit::test
