#include "pipeline/prepare_parts.h"

#include <chrono>
#include <cmath>
#include <sstream>
#include <exception>
#include <tbb/parallel_invoke.h>

#include "pipeline/part_mesh.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Every descriptor (the skeletal density, the indicator, the voxel map) is of the part's
// inside: a sheet or a surface that encloses no volume has none, and its fields would be
// noise of the winding number's edge.
void check_encloses_volume(const PartSpec& spec, const Scene& scene, const MeshReport& report) {
  const Eigen::Vector3d box = report.bbox_max - report.bbox_min;
  const double diagonal = box.norm();
  if (std::abs(report.enclosed_volume) > 1e-9 * diagonal * diagonal * diagonal) return;
  std::ostringstream m;
  m << "part '" << spec.name << "' encloses no volume (" << report.enclosed_volume << " " << scene.units
    << "^3 in a box of " << box.x() << " x " << box.y() << " x " << box.z() << " " << scene.units << ", "
    << report.triangle_count << " triangles, " << report.boundary_edges
    << " open edges): the descriptors need a solid, not a sheet or an open surface";
  throw Error(m.str());
}

PreparedPart prepare(const PartSpec& spec, const Scene& scene) {
  const auto start = std::chrono::steady_clock::now();
  PreparedPart part;
  PartMesh built = build_part_mesh(spec, scene);
  part.mesh = std::move(built.mesh);
  part.faces = std::move(built.faces);
  part.cad = std::move(built.cad);
  part.report = validate_mesh(part.mesh);
  check_encloses_volume(spec, scene, part.report);
  part.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return part;
}

}  // namespace

PreparedParts prepare_parts(const Scene& scene) {
  PreparedParts parts;
  std::exception_ptr error1, error2;
  tbb::parallel_invoke(
      [&] {
        try {
          parts.part1 = prepare(scene.part1, scene);
        } catch (...) {
          error1 = std::current_exception();
        }
      },
      [&] {
        try {
          parts.part2 = prepare(scene.part2, scene);
        } catch (...) {
          error2 = std::current_exception();
        }
      });
  if (error1) std::rethrow_exception(error1);
  if (error2) std::rethrow_exception(error2);
  return parts;
}

}  // namespace snapfit
