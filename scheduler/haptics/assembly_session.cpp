#include "scheduler/haptics/assembly_session.h"

#include <algorithm>
#include <chrono>

#include "scheduler/haptics/assembly_verdict.h"
#include "scheduler/haptics/scripted_device.h"
#include "snapfit/error.h"

namespace snapfit {

SessionResult run_scripted_assembly(const Scene& scene, const Mesh& part1_mesh, const Mesh& part2_mesh, double spacing,
                                    QueryEngine& engine, const TuningResult& tuning, const SessionOptions& options) {
  if (scene.trajectory.keyframes.empty())
    throw Error(scene.source_path + ": no trajectory: a scripted assembly needs one (or use a real device)");
  const auto built = std::chrono::steady_clock::now();
  std::string contact_off;
  std::shared_ptr<const RigidContactModel> contact =
      rigid_contact_for(scene, part1_mesh, part2_mesh, spacing, &contact_off);
  const double build_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
  double force_scale = 0;
  LoopConfig config =
      loop_config_for(scene, part2_mesh, spacing, engine, tuning, force_scale, contact, options.contact_ms);
  config.in_region = region_guard(scene_region(scene, part1_mesh, part2_mesh, spacing));
  const double setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - built).count();
  SessionResult out = run_scripted_session(scene, part2_mesh, spacing, config, wrench_evaluator(engine), options);
  out.setup_s = setup_s;
  out.force_scale = force_scale;
  out.contact = std::move(contact);
  out.contact_build_s = build_s;
  out.contact_off = contact_off;
  if (scene.assembled_pose)
    out.fit_stiffness =
        rendered_stiffness(wrench_evaluator(engine), config.geometry_gain, config.contact, config.coupling,
                           *scene.assembled_pose);
  return out;
}

Eigen::Vector3d insertion_direction(const Trajectory& trajectory, const Pose& target) {
  const auto& k = trajectory.keyframes;
  for (std::size_t i = k.size(); i >= 2; --i) {
    const Eigen::Vector3d step = k[i - 1].pose.translation - k[i - 2].pose.translation;
    if (step.norm() > 1e-9) return step.normalized();
  }
  if (!k.empty() && (target.translation - k.front().pose.translation).norm() > 1e-9)
    return (target.translation - k.front().pose.translation).normalized();
  return Eigen::Vector3d::UnitZ();
}

SessionResult session_before_loop(const Scene& scene, double spacing, const LoopConfig& config) {
  SessionResult out;
  out.limits = device_limits_for(scene);
  out.target = scene.assembled_pose.value_or(scene.trajectory.keyframes.empty() ? scene.part2.pose
                                                                                : scene.trajectory.keyframes.back().pose);
  out.position_tolerance = scene.haptics.success_position.value_or(spacing);  // the descriptors' resolution
  out.angle_tolerance_deg = scene.haptics.success_angle_deg;
  out.coupling = config.coupling;
  out.geometry_gain = config.geometry_gain;
  out.contact_ms = config.contact_ms;
  out.max_force_rate_n_per_s = config.max_force_rate_n_per_s;
  out.start_modes = config.modes.levels.empty() ? 0 : config.modes.levels.back();
  return out;
}

void judge_session_end(SessionResult& out, const Scene& scene, const Mesh& part2_mesh) {
  const AssemblyJudge judge(part2_mesh, out.target, out.position_tolerance, out.angle_tolerance_deg);
  const AssemblyVerdict verdict = judge.judge(out.loop.final_part.pose);
  out.final_error = verdict.pose;
  out.surface_deviation = verdict.surface.distance;
  out.surface_deviation_at = verdict.surface.where;
  out.evaluated = scene.assembled_pose.has_value();
  out.assembled = out.evaluated && verdict.assembled;
  out.insertion_direction = insertion_direction(scene.trajectory, out.target);
  const Eigen::Vector3d d = out.loop.final_part.pose.translation - out.target.translation;
  out.axial_error = d.dot(out.insertion_direction);
  out.lateral_error = (d - out.axial_error * out.insertion_direction).norm();
  if (!out.loop.log.empty()) out.final_force = out.loop.log.back().sent.force;
}

PriorityRequest loop_priority(const PriorityRequest& request, LoopWait wait) {
  PriorityRequest priority = request;
  if (wait == LoopWait::spin) priority.realtime_priority = 0;  // a spinning SCHED_FIFO thread is throttled
  return priority;
}

SessionResult run_scripted_session(const Scene& scene, const Mesh& part2_mesh, double spacing, LoopConfig config,
                                   const WrenchEvaluator& evaluator, const SessionOptions& options) {
  if (scene.trajectory.keyframes.empty())
    throw Error(scene.source_path + ": no trajectory: a scripted assembly needs one (or use a real device)");
  SessionResult out = session_before_loop(scene, spacing, config);
  const Trajectory& t = scene.trajectory;
  if (options.duration_s) config.duration_s = *options.duration_s;
  config.keep_log = options.keep_log;

  ScriptedDevice device(t, out.limits, options.loop_back);
  BodyState part;
  part.pose = device.read(0).pose;  // the part starts in the user's hand
  const bool raise =
      (options.priority.nice_value != 0 || options.priority.realtime_priority > 0) && !options.simulated_time;
  PriorityChange priority;
  if (raise) priority = raise_process_priority(loop_priority(options.priority, options.wait));
  out.priority = priority;
  out.wait = options.wait;
  {
    // Warm-up at the loop's m' and the first pose, as a haptics program does before it
    // engages the device: the runtime's threads, now at their new priority, and the
    // caches see the query once before the first deadline.
    if (!options.simulated_time)
      for (int i = 0; i < options.warmup_queries; ++i) evaluator.evaluate(part.pose);
    HapticLoopThread loop(device, evaluator, config, part,
                          options.simulated_time ? simulated_loop_clock() : steady_loop_clock(options.wait));
    out.loop = loop.join();
  }
  if (raise) restore_process_priority(priority);
  judge_session_end(out, scene, part2_mesh);
  return out;
}

}  // namespace snapfit
