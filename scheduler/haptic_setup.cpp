#include "scheduler/haptic_setup.h"

#include <algorithm>
#include <cmath>

#include "mesh/mesh_mass_properties.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/auto_tune.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"

namespace snapfit {

CouplingParams coupling_for(const Scene& scene, const Mesh& part2_mesh) {
  const HapticsParams& h = scene.haptics;
  const double u = metres_per_unit(scene.units);
  const double r2 = solid_moments(part2_mesh).mean_square_radius * u * u;  // m^2
  const double inertia = (2.0 / 3.0) * h.mass_kg * r2;
  const double rot_stiffness = h.rot_stiffness_nm_per_rad.value_or(h.stiffness_n_per_m * inertia / h.mass_kg);
  return make_coupling(u, h.mass_kg, inertia, h.stiffness_n_per_m, rot_stiffness, h.damping_ratio);
}

DeviceLimits device_limits_for(const Scene& scene) {
  return DeviceLimits{scene.haptics.max_force_n, scene.haptics.max_torque_nm};
}

double geometry_gain_for(const Scene& scene, double spacing, double force_scale) {
  const HapticsParams& h = scene.haptics;
  if (h.geometry_gain) return *h.geometry_gain;
  if (!(std::isfinite(force_scale) && force_scale > 0))
    throw Error("haptics: the geometric force near the reference pose is " + std::to_string(force_scale) +
                ", so no geometric gain can be derived from it; set haptics.geometry_gain in the scene");
  return h.geometry_strength * h.stiffness_n_per_m * spacing * metres_per_unit(scene.units) / force_scale;
}

Pose gain_reference_pose(const Scene& scene) { return scene.assembled_pose.value_or(scene.part2.pose); }

std::vector<Pose> gain_probe_poses(const Scene& scene, double spacing) {
  std::vector<Pose> poses;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      Pose p = gain_reference_pose(scene);
      p.translation[axis] += sign * 2.0 * spacing;
      poses.push_back(p);
    }
  return poses;
}

PoseError pose_error(const Pose& actual, const Pose& target) {
  PoseError e;
  e.position = (actual.translation - target.translation).norm();
  e.angle_deg = rotation_between(actual.rotation, target.rotation).norm() * 180.0 / M_PI;
  return e;
}

LoopConfig scene_loop_config(const Scene& scene, const CouplingParams& coupling) {
  LoopConfig config;
  config.rate_hz = scene.loop_rate_hz;
  const Trajectory& t = scene.trajectory;
  config.duration_s =
      t.keyframes.empty() ? 0.0 : t.keyframes.back().time_s - t.keyframes.front().time_s + scene.haptics.settle_s;
  config.budget_ms = scene.frame_budget_ms;
  config.coupling = coupling;
  return config;
}

LoopConfig loop_config_for(const Scene& scene, const Mesh& part2_mesh, double spacing, QueryEngine& engine,
                           const TuningResult& tuning, double& force_scale,
                           std::shared_ptr<const RigidContactModel> contact) {
  LoopConfig config = scene_loop_config(scene, coupling_for(scene, part2_mesh));
  config.contact = contact_evaluator(std::move(contact));
  engine.set_modes(tuning.chosen_modes);
  force_scale = 0;
  for (const QueryResult& r : engine.query_batch(gain_probe_poses(scene, spacing)))
    if (r.flags == query_ok) force_scale = std::max(force_scale, r.force.norm());
  config.geometry_gain = geometry_gain_for(scene, spacing, force_scale);
  config.modes.levels = loop_levels(tuning);
  const CostModel model = tuning.model;
  config.modes.predicted_ms = [model](std::size_t m) { return model.predict_ms(m); };
  return config;
}

LoopConfig loop_config(const Assembly& assembly, QueryEngine& engine, const TuningResult& tuning) {
  const AssemblyPair& pair = assembly.pair();
  double force_scale = 0;
  return loop_config_for(pair.scene, pair.part(2).mesh, pair.grids.spacing, engine, tuning, force_scale,
                         rigid_contact_for(pair.scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing));
}

}  // namespace snapfit
