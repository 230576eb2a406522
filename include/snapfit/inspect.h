#pragma once
// What snapfit makes of a part file and of a scene before any device work: a mesh's
// validation report (and, for STEP and IGES, what the CAD import did), and a scene's
// parts built and validated with the compute plan it implies, as `snapfit mesh-info`
// and `snapfit scene-check` print them.
//
//   snapfit::MeshFileRequest request;
//   request.file = "part.step";
//   snapfit::MeshFileReport report = snapfit::inspect_mesh_file(request);
//   std::cout << snapfit::format_mesh_report(report.mesh);
#include <Eigen/Core>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "snapfit/mesh.h"
#include "snapfit/scene.h"

namespace snapfit {

// Validation report of a triangle mesh. Vertices at identical positions are welded before
// edges are counted, so a triangle soup (STL) is judged by its geometry, not by its index buffer.
struct MeshReport {
  std::size_t vertex_count = 0;  // distinct vertex positions (after welding)
  std::size_t triangle_count = 0;
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
  std::size_t degenerate_triangles = 0;  // repeated vertex or (near-)zero area
  std::size_t boundary_edges = 0;        // edges with one incident triangle (open mesh)
  std::size_t non_manifold_edges = 0;    // edges with more than two incident triangles
  std::size_t inconsistent_edges = 0;    // two triangles traverse the edge the same way
  double surface_area = 0.0;
  double enclosed_volume = 0.0;  // signed, divergence theorem; < 0: inward normals
  bool watertight() const { return boundary_edges == 0 && non_manifold_edges == 0 && inconsistent_edges == 0; }
};

// Human-readable multi-line text, and one JSON object, of the same report.
std::string format_mesh_report(const MeshReport& report);
std::string mesh_report_json(const MeshReport& report);

// What a CAD import did: the file's solids and units, the solid it tessellated, the
// deflections it used and what came out.
struct CadFacts {
  std::string format;               // "STEP" or "IGES"
  std::string file_unit;            // the length unit the file declares, as it spells it
  std::vector<std::string> solids;  // every solid in the file, by the names a part may give
  std::string solid;                // the one tessellated
  std::size_t faces = 0;            // B-rep faces of that solid
  // Of those, the analytic faces the VPS - constraint hybrid reads (tori only keep their
  // points unlabelled), and the faces on other surfaces (spheres, B-splines), which give none.
  std::size_t planes = 0, cylinders = 0, cones = 0, tori = 0, other_faces = 0;
  double linear_deflection = 0;  // used, in output units: largest distance of the mesh from the surface
  double angular_deflection_deg = 0;
  std::string deflection_source;  // where linear_deflection came from, e.g. "0.025 x grid spacing 0.6"
  std::size_t triangles = 0;      // produced
  double exact_volume = 0;        // of the B-rep solid (OpenCASCADE's integration), output units^3
  double exact_area = 0;          // of its faces, output units^2
};

// Multi-line text (one "cad ...: value" line per fact) and one JSON object.
std::string format_cad_facts(const CadFacts& facts);
std::string cad_facts_json(const CadFacts& facts);

// STEP (.step, .stp) or IGES (.iges, .igs), by the file name's extension.
bool is_cad_file(const std::string& path);

// The default angular deflection of a STEP or IGES tessellation, degrees.
constexpr double kDefaultAngularDeflectionDeg = 30.0;

struct MeshFileRequest {
  std::string file;    // any format Assimp reads, or STEP/IGES through OpenCASCADE
  double scale = 1.0;  // multiplies every coordinate (file units -> your units)
  // STEP and IGES only:
  double metres_per_unit = 1e-3;     // the output's length unit (metres_per_unit in scene.h)
  std::string units = "mm";          // its name, for messages
  std::string solid;                 // the solid to tessellate, for a file with several
  std::optional<double> deflection;  // linear deflection in output units (default: the grid spacing / 40)
  std::optional<double> spacing;     // grid spacing the default deflection is tied to
  int resolution = 64;               // without spacing: a grid of this many points along the solid's longest side
  double angular_deflection_deg = kDefaultAngularDeflectionDeg;
};

struct MeshFileReport {
  MeshReport mesh;
  std::optional<CadFacts> cad;  // STEP and IGES files
};

// Loads (or tessellates) the file and validates the mesh. Throws snapfit::Error naming
// the file and the problem.
MeshFileReport inspect_mesh_file(const MeshFileRequest& request);

// A scene's part as the pipeline builds it: in the part's own frame, scene units.
struct PartCheck {
  MeshReport mesh;
  std::optional<CadFacts> cad;  // STEP and IGES parts
  double seconds = 0;           // wall time to load or generate and validate
};

struct SceneCheck {
  PartCheck part1, part2;
  std::vector<std::string> plan;      // what the engine will compute: one sentence per decision, with its reason
  std::vector<std::string> warnings;  // settings that will cost accuracy, with what to change
};

// Builds and validates both parts (no device) and plans the computation. Throws
// snapfit::Error naming the part when a mesh cannot be made.
SceneCheck check_scene(const Scene& scene);

// A scene part's triangle mesh as the engine builds it (loaded, tessellated from STEP or
// IGES, or generated), in the part's own frame, scene units.
using PartGeometry = Mesh;

// Part 1 or 2 of the scene. Throws snapfit::Error naming the part when its mesh cannot be
// made, or when `part` is not 1 or 2.
PartGeometry part_geometry(const Scene& scene, int part);

// The scene, its parts (size, box, volume, watertightness, CAD facts, warnings) and the
// compute plan, as `snapfit scene-check` prints them.
std::string scene_summary_text(const Scene& scene, const SceneCheck& check);

}  // namespace snapfit
