#include "pipeline/scene_summary.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "pipeline/scene_check.h"

namespace snapfit {
namespace {

void print_part(std::ostream& out, const char* role, const PartSpec& spec, const PartCheck& part,
                const std::string& units) {
  const MeshReport& r = part.mesh;
  out << role << " '" << spec.name
      << "': " << (spec.mesh_path ? *spec.mesh_path : "procedural " + spec.procedural->type) << "\n"
      << "    " << r.triangle_count << " triangles, box [" << r.bbox_min.transpose() << "] .. ["
      << r.bbox_max.transpose() << "] " << units << ", volume " << r.enclosed_volume << " " << units << "^3, "
      << (r.watertight() ? "watertight" : "NOT watertight") << ", " << r.degenerate_triangles
      << " degenerate triangles (" << std::setprecision(3) << part.seconds * 1000 << " ms)\n";
  out << std::setprecision(6);
  if (const std::optional<CadFacts>& cad = part.cad) {
    out << "    " << cad->format << " (length unit " << cad->file_unit << "): solid '" << cad->solid << "' of "
        << cad->solids.size() << ", " << cad->faces << " faces, tessellated at deflection " << cad->linear_deflection
        << " " << units << " (" << cad->deflection_source << ") and " << cad->angular_deflection_deg
        << " deg; exact volume " << cad->exact_volume << " " << units << "^3\n";
  }
  if (!r.watertight()) {
    out << "    warning: " << r.boundary_edges << " open edges, " << r.non_manifold_edges << " non-manifold edges, "
        << r.inconsistent_edges << " inconsistently oriented edges; the winding number still classifies points, "
        << "but descriptors near those edges are less reliable\n";
  }
  if (r.enclosed_volume < 0) out << "    warning: negative volume, the normals point inward\n";
}

}  // namespace

void print_scene_summary(std::ostream& out, const Scene& scene, const PreparedParts& parts, const ComputePlan& plan) {
  print_scene_summary(out, scene, scene_check_of(parts, plan));
}

void print_scene_summary(std::ostream& out, const Scene& scene, const SceneCheck& check) {
  out << "scene '" << scene.name << "' (" << scene.source_path << "), units " << scene.units << "\n";
  print_part(out, "part 1 (fixed)", scene.part1, check.part1, scene.units);
  print_part(out, "part 2 (moving)", scene.part2, check.part2, scene.units);
  out << "motion " << (scene.motion == Motion::six_dof ? "6-DOF" : "translation only") << ", frame budget "
      << scene.frame_budget_ms << " ms at " << scene.loop_rate_hz << " Hz, " << scene.trajectory.keyframes.size()
      << " trajectory keyframes";
  if (!scene.trajectory.keyframes.empty()) out << " over " << scene.trajectory.keyframes.back().time_s << " s";
  out << "\nplan:\n";
  for (const std::string& line : check.plan) out << "  - " << line << "\n";
  for (const std::string& warning : check.warnings) out << "warning: " << warning << "\n";
}

void print_fields_summary(std::ostream& out, const PartFieldsResult& result) {
  const DescriptorFields& f = result.fields;
  const auto precision = out.precision(3);
  if (result.from_cache) {
    out << "    fields loaded from the cache\n";
  } else {
    out << "    computed in " << f.seconds << " s (distance " << f.distance_seconds << " s, winding number "
        << f.winding_seconds << " s, skeletal density " << f.density_seconds << " s; " << f.refined_triangles
        << " triangles after refinement)\n";
  }
  if (!f.density_bound.empty()) {
    double mean_bound = 0, mean_s = 0;
    for (std::size_t i = 0; i < f.density_bound.size(); ++i) {
      mean_bound += f.density_bound[i];
      mean_s += std::abs(f.skeletal_density[i]);
    }
    out << "    skeletal density error bound: mean " << mean_bound / f.density_bound.size() << " (mean |s| "
        << mean_s / f.density_bound.size() << "), max "
        << *std::max_element(f.density_bound.begin(), f.density_bound.end()) << "\n";
  }
  out.precision(precision);
}

std::string scene_summary_text(const Scene& scene, const SceneCheck& check) {
  std::ostringstream out;
  print_scene_summary(out, scene, check);
  return out.str();
}

std::string fields_summary_text(const PartFieldsResult& result) {
  std::ostringstream out;
  print_fields_summary(out, result);
  return out.str();
}

}  // namespace snapfit
