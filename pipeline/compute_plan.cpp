#include "pipeline/compute_plan.h"

#include <sstream>

namespace snapfit {
namespace {

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

// Where each part's spectrum comes from, and which path docs/spheres.md recommends
// ("Which path wins where": the grid path, at every setting measured).
void add_spectrum_source(ComputePlan& plan, const Scene& scene) {
  const PartDescriptorSpec* parts[2] = {&scene.part1.descriptor, &scene.part2.descriptor};
  bool any_spheres = false;
  for (int p = 0; p < 2; ++p) {
    const PartDescriptorSpec& d = *parts[p];
    if (d.source != SpectrumSource::spheres) continue;
    any_spheres = true;
    const std::string part = "part " + std::to_string(p + 1);
    plan.lines.push_back(part + "'s spectrum: seed 001's balls (tolerance " +
                         (d.tolerance ? number(*d.tolerance) : std::string("the grid spacing")) + ", protrusion " +
                         number(d.protrusion) + "), their analytic transforms summed by " +
                         (d.method == "auto" ? std::string("the direct NDFT or the type-1 NUFFT, whichever the "
                                                           "ball count and lattice make faster")
                                             : "the " + d.method + " NDFT"));
    plan.warnings.push_back(part +
                            " takes its spectrum from balls: \"source\": \"grid\" is recommended. The balls' "
                            "density counts overlapping balls with multiplicity, so its spectrum is not the part's "
                            "indicator's, and the decomposition itself needs the part's fields on a grid as fine "
                            "as the grid path's: slower and less accurate at every setting measured "
                            "(docs/spheres.md \"Which path wins where\")");
  }
  if (!any_spheres)
    plan.lines.push_back(
        "spectrum source: the grid for both parts (fields sampled, then FFT), the path docs/spheres.md recommends "
        "over seed 001's balls");
}

// Voxmap PointShell's plan (scheduler/vps/vps_method.h): no fields, spectra or modes.
ComputePlan vps_plan(const Scene& scene, double grid_spacing) {
  ComputePlan plan;
  plan.rotation = scene.motion == Motion::six_dof;
  plan.force = true;
  plan.torque = plan.rotation;
  const VpsParams& v = scene.vps;
  const std::string voxel = v.voxel_size       ? number(*v.voxel_size) + " " + scene.units
                            : grid_spacing > 0 ? number(grid_spacing) + " " + scene.units + " (the grid spacing)"
                                               : std::string("the grid spacing");
  plan.lines.push_back(
      "method: Voxmap PointShell (seed 002 section 4.1): no descriptor fields, spectra or Fourier modes");
  plan.lines.push_back("part 1: a voxmap, voxel " + voxel + ", with surface, interior and " +
                       std::to_string(v.proximity_layers) + " proximity layers");
  plan.lines.push_back("part 2: a point shell with inward normals, " + number(v.shell_density) +
                       " points per voxel along its surface");
  plan.lines.push_back(
      "per frame: each shell point in a surface or interior voxel pushes part 2 along its normal "
      "(tangent-plane force, k_ff " +
      number(v.stiffness_n_per_m) + " N/m a point); points approaching through proximity voxels are braked");
  if (scene.method == Method::vps_hybrid)
    plan.lines.push_back(
        "hybrid (seed 002 chapter 5): voxels and shell points carry their analytic faces; "
        "concentric and planar constraints between contacting faces are phased in, "
        "F = F_C (1 - w) + F_A w with w = min(1, x / " +
        number(scene.vps.hybrid.x_full) + ") (eq. 13-19), region '" +
        hybrid_region_name(scene.vps.hybrid.region) +
        "'; a part without analytic faces runs as plain VPS");
  plan.lines.push_back(std::string("outputs per frame: force") + (plan.torque ? ", torque" : "") +
                       " (and the points' penalty energy)" +
                       (scene.method == Method::vps_hybrid ? "; the engaged constraint and its weight x" : ""));
  return plan;
}

}  // namespace

ComputePlan plan_computation(const Scene& scene, double grid_spacing) {
  if (uses_vps(scene.method)) return vps_plan(scene, grid_spacing);
  ComputePlan plan;
  plan.skeletal_density = scene.descriptor.kind == DescriptorKind::skeletal_density;
  plan.rotation = scene.motion == Motion::six_dof;
  plan.force = scene.outputs.force;
  plan.torque = scene.outputs.torque && plan.rotation;

  if (plan.skeletal_density) {
    plan.lines.push_back(
        "fields: winding number, signed distance and skeletal density (sigma " + number(scene.descriptor.sigma) +
        ") for both parts, affinity rho = i*lambda*s "
        "(lambda_in " +
        number(scene.descriptor.lambda_in) + ", lambda_out " + number(scene.descriptor.lambda_out) + ")");
  } else {
    plan.lines.push_back(
        "fields: winding number (indicator) only: the scene asks for collision response, "
        "so no signed distance or skeletal density is computed");
  }
  add_spectrum_source(plan, scene);
  plan.lines.push_back(plan.rotation
                           ? "spectra: both parts', and part 2's deconvolved for its exact rotation (6-DOF motion)"
                           : "spectra: both parts' (translation-only motion: part 2 never turns)");
  plan.lines.push_back(plan.rotation
                           ? "per frame: part 2's spectrum interpolated at the rotated frequencies (tricubic); "
                             "snapfit accuracy measures the exact-rotation product beside it"
                           : "per frame: phase sum over a precomputed product (translation-only motion, "
                             "no spectrum rotation)");
  if (plan.torque)
    plan.lines.push_back("torque: the derivative of the rendered energy under rotation (no extra fields)");
  std::string outputs = "energy";
  if (plan.force) outputs += ", force";
  if (plan.torque) outputs += ", torque";
  plan.lines.push_back("outputs per query: " + outputs);
  return plan;
}

}  // namespace snapfit
