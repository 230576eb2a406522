#include "scheduler/haptics/haptic_setup.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "core/quantile.h"
#include "mesh/mesh_mass_properties.h"
#include "pipeline/assembly_access.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/modes/mode_tuning.h"
#include "scheduler/haptics/parallel_contact.h"
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
  config.max_force_rate_n_per_s = scene.haptics.max_force_rate_n_per_s;
  config.trust.enabled = scene.haptics.vouch;
  return config;
}

double contact_cost_ms(const std::function<ContactWrench(const Pose&)>& contact, const RigidContactModel& model,
                       const Scene& scene, int repetitions) {
  // The reference pose and the reference moved by one fine distance spacing along each
  // axis: as deep into part 1 as the loop's part goes (the contact holds it within ~1).
  std::vector<Pose> poses = gain_probe_poses(scene, 0.5 * model.part1_distance.fine_spacing());
  poses.push_back(gain_reference_pose(scene));
  std::vector<double> ms;
  ms.reserve(poses.size() * std::size_t(std::max(1, repetitions)));
  volatile double kept = 0;  // the result is used, so the call is timed
  for (int r = 0; r < std::max(1, repetitions); ++r)
    for (const Pose& pose : poses) {
      const auto start = std::chrono::steady_clock::now();
      kept = contact(pose).energy_j;
      ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
  (void)kept;
  return quantile(ms, 0.99);
}

TuningResult tuning_beside_contact(const TuningResult& tuning, double contact_ms) {
  if (!(contact_ms > 0) || tuning.points.empty()) return tuning;
  // The frame's work is the query plus the contact: the query's target shrinks by the
  // contact's time, (budget - b)(1 - margin) = budget (1 - margin) - contact.
  const double budget = tuning.budget_ms - contact_ms / (1.0 - tuning.margin);
  if (!(budget > 0)) {  // the contact alone fills the frame: the smallest m' measured
    TuningResult r = pick_modes(tuning.points, tuning.budget_ms, tuning.margin);
    r.chosen_modes = r.points.front().modes;
    r.fits = false;
    return r;
  }
  TuningResult r = pick_modes(tuning.points, budget, tuning.margin);
  r.budget_ms = tuning.budget_ms;  // the frame's budget stays the scene's
  r.created = tuning.created;
  return r;
}

LoopConfig loop_config_for(const Scene& scene, const Mesh& part2_mesh, double spacing, QueryEngine& engine,
                           const TuningResult& tuned, double& force_scale,
                           std::shared_ptr<const RigidContactModel> contact, std::optional<double> contact_ms) {
  LoopConfig config = scene_loop_config(scene, coupling_for(scene, part2_mesh));
  if (contact) {
    config.contact = contact_evaluator(contact);
    config.contact_ms = contact_ms ? *contact_ms : contact_cost_ms(config.contact, *contact, scene);
  }
  const TuningResult tuning = tuning_beside_contact(tuned, config.contact_ms);
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
  const AssemblyPair& pair = AssemblyAccess::pair(assembly);
  double force_scale = 0;
  LoopConfig config =
      loop_config_for(pair.scene, pair.part(2).mesh, pair.grids.spacing, engine, tuning, force_scale,
                      rigid_contact_for(pair.scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing));
  config.in_region = region_guard(pair.region);
  return config;
}

std::function<bool(const Pose&)> region_guard(const ReachRegion& region) {
  if (!region.bounded) return nullptr;
  ReachRegion check;  // only what the per-frame test reads
  check.bounded = true;
  check.box = region.box;
  check.part2_box = region.part2_box;
  return [check](const Pose& pose) { return pose_in_region(check, pose); };
}

}  // namespace snapfit
