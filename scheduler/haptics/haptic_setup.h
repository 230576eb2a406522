#pragma once
// From a scene's `haptics` section (snapfit/scene.h HapticsParams) to what the haptic loop
// needs: the virtual coupling, the device limits, the geometric gain, and the test of
// whether a run ended assembled.
#include <functional>
#include <memory>
#include <optional>
#include <vector>

#include "mesh/mesh.h"
#include "pipeline/reach_region.h"
#include "scheduler/haptics/rigid_contact.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "snapfit/haptic_device.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/pose.h"
#include "snapfit/scene.h"
#include "snapfit/tuning.h"

namespace snapfit {

// Isotropic inertia of part 2 about its reference point (frame origin),
// I = (2/3) m <|q|^2> (a uniform solid's trace(J) / 3), and k_R = k_T r_g^2 with
// r_g^2 = I / m unless the scene sets k_R; damping from the damping ratio.
CouplingParams coupling_for(const Scene& scene, const Mesh& part2_mesh);

DeviceLimits device_limits_for(const Scene& scene);

// N per engine force unit. The scene's geometry_gain when set; otherwise chosen so that
// `force_scale` (engine units) maps to strength * k_T * h: with the force scale measured
// 2 grid spacings off the reference pose (gain_probe_poses), the geometric stiffness of
// the fit is then about strength / 2 times the coupling's, so the fit pulls the part
// home and resists collisions about as firmly as the coupling holds it, at any scale
// or m'. Throws snapfit::Error when the force scale is 0 or not finite.
double geometry_gain_for(const Scene& scene, double spacing, double force_scale);

// The pose the gain is calibrated at: the assembled pose, else part 2's initial pose.
Pose gain_reference_pose(const Scene& scene);

// The reference pose moved by +-2 h along each axis of part 1's frame (6 poses); the
// force scale is the largest engine force magnitude among them.
std::vector<Pose> gain_probe_poses(const Scene& scene, double spacing);

// What every method's loop takes from the scene: rate, frame budget, the coupling, and
// the duration (the trajectory's length plus haptics.settle_s; 0 without a trajectory).
LoopConfig scene_loop_config(const Scene& scene, const CouplingParams& coupling);

// The rigid contact's time per frame near the fit: p99 of `contact` (the evaluator of
// `model` the loop calls, scheduler/haptics/parallel_contact.h) in ms over
// `repetitions` rounds of the gain's reference pose and that pose moved by one fine
// distance spacing along +-x, +-y, +-z (into part 1 about as deep as the contact lets
// the loop's part go).
double contact_cost_ms(const std::function<ContactWrench(const Pose&)>& contact, const RigidContactModel& model,
                       const Scene& scene, int repetitions = 30);

// The tuning with the contact's time taken out of the frame: m' picked again from the
// measured points so that query + contact fit the budget with the tuning's margin (the
// smallest m' measured when the contact alone fills it). Unchanged for contact_ms 0.
TuningResult tuning_beside_contact(const TuningResult& tuning, double contact_ms);

// The loop's configuration for `scene` (include/snapfit/haptic_loop.h loop_config):
// `engine` is set to the tuned m' and probed at gain_probe_poses for the gain; the
// largest force it saw goes to `force_scale`.
// `contact`, when not null, is the rigid contact the loop adds (scheduler/haptics/rigid_contact.h);
// its time (`contact_ms` when given, else measured by contact_cost_ms; in
// LoopConfig::contact_ms) is taken out of the frame's budget before the loop's m' levels
// are set (tuning_beside_contact).
LoopConfig loop_config_for(const Scene& scene, const Mesh& part2_mesh, double spacing, QueryEngine& engine,
                           const TuningResult& tuning, double& force_scale,
                           std::shared_ptr<const RigidContactModel> contact = nullptr,
                           std::optional<double> contact_ms = std::nullopt);

// LoopConfig::in_region for a region (pipeline/reach_region.h); null when it is not bounded.
std::function<bool(const Pose&)> region_guard(const ReachRegion& region);

}  // namespace snapfit
