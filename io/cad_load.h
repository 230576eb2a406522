#pragma once
// CAD part import through OpenCASCADE: STEP (.step, .stp) and IGES (.iges, .igs) files,
// their B-rep solids tessellated into a watertight triangle mesh at a deflection tied to
// the grid the descriptors are sampled on.
#include <optional>
#include <string>

#include "io/cad_facts.h"
#include "io/cad_format.h"
#include "mesh/analytic_faces.h"
#include "mesh/mesh.h"
#include "snapfit/scene.h"

namespace snapfit {

// The default linear deflection (largest distance between the mesh and the B-rep
// surface) as a fraction of the grid spacing, and the default angular deflection (largest
// angle between the normals of neighbouring triangles of one face, and between a
// triangle and the surface). docs/scenes.md "CAD parts" gives the measurements behind them.
constexpr double kDefaultDeflectionPerSpacing = 0.025;

struct CadImportOptions {
  // The output's length unit (snapfit/scene.h metres_per_unit): the file's own unit is
  // converted to it, then every coordinate is multiplied by `scale`.
  double metres_per_unit = 1e-3;
  std::string units = "mm";  // its name, for messages
  double scale = 1.0;
  // The solid to take, by one of the names CadFacts::solids lists; needed when the file
  // holds more than one.
  std::optional<std::string> solid;
  // Output units; default kDefaultDeflectionPerSpacing x the spacing `grid` gives. A grid
  // given by resolution takes the spacing that resolution gives over this solid's box
  // alone: at most the scene's spacing (which spans both parts), so never coarser.
  std::optional<double> linear_deflection;
  double angular_deflection_deg = kDefaultAngularDeflectionDeg;
  GridParams grid;
};

struct CadMesh {
  Mesh mesh;  // output units, outward normals, vertices shared between faces
  // The solid's planes, cylinders and cones in output units (io/occt_shapes.h
  // analytic_faces_of), for the VPS - constraint hybrid; faces on other surfaces give none.
  std::vector<AnalyticFace> faces;
  CadFacts facts;
};

// Reads the file, picks its solid (faces that are not in a solid are sewn into closed
// shells first: IGES files usually hold faces only), tessellates it with OpenCASCADE's
// BRepMesh (one thread) and welds the faces' meshes along their shared edges, and
// classifies each B-rep face's surface (plane, cylinder, cone or other). Runs in the
// import child with the limits of io/import_child.h. Throws snapfit::Error naming the file
// for a missing, empty, truncated or malformed file, a file with no closed solid, one with
// several and no `solid` (the message lists them), an unknown `solid`, or a bad option.
CadMesh load_cad_mesh(const std::string& path, const CadImportOptions& options);

}  // namespace snapfit
