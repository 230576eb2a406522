#include "cli/scene_summary.h"

#include <iomanip>

namespace snapfit::cli {
namespace {

void print_part(std::ostream& out, const char* role, const PartSpec& spec, const PreparedPart& part, const std::string& units) {
  const MeshReport& r = part.report;
  out << role << " '" << spec.name << "': "
      << (spec.mesh_path ? *spec.mesh_path : "procedural " + spec.procedural->type) << "\n"
      << "    " << r.triangle_count << " triangles, box [" << r.bbox_min.transpose() << "] .. ["
      << r.bbox_max.transpose() << "] " << units << ", volume " << r.enclosed_volume << " " << units << "^3, "
      << (r.watertight() ? "watertight" : "NOT watertight") << ", " << r.degenerate_triangles
      << " degenerate triangles (" << std::setprecision(3) << part.seconds * 1000 << " ms)\n";
  out << std::setprecision(6);
  if (!r.watertight()) {
    out << "    warning: " << r.boundary_edges << " open edges, " << r.non_manifold_edges << " non-manifold edges, "
        << r.inconsistent_edges << " inconsistently oriented edges; the winding number still classifies points, "
        << "but descriptors near those edges are less reliable\n";
  }
  if (r.enclosed_volume < 0) out << "    warning: negative volume, the normals point inward\n";
}

}  // namespace

void print_scene_summary(std::ostream& out, const Scene& scene, const PreparedParts& parts, const ComputePlan& plan) {
  out << "scene '" << scene.name << "' (" << scene.source_path << "), units " << scene.units << "\n";
  print_part(out, "part 1 (fixed)", scene.part1, parts.part1, scene.units);
  print_part(out, "part 2 (moving)", scene.part2, parts.part2, scene.units);
  out << "motion " << (scene.motion == Motion::six_dof ? "6-DOF" : "translation only") << ", frame budget "
      << scene.frame_budget_ms << " ms at " << scene.loop_rate_hz << " Hz, "
      << scene.trajectory.keyframes.size() << " trajectory keyframes";
  if (!scene.trajectory.keyframes.empty()) out << " over " << scene.trajectory.keyframes.back().time_s << " s";
  out << "\nplan:\n";
  for (const std::string& line : plan.lines) out << "  - " << line << "\n";
}

}  // namespace snapfit::cli
