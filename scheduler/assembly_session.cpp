#include "scheduler/assembly_session.h"

#include <algorithm>

#include "snapfit/error.h"
#include "scheduler/scripted_device.h"

namespace snapfit {

SessionResult run_scripted_assembly(const Scene& scene, const Mesh& part2_mesh, double spacing,
                                    QueryEngine& engine, const TuningResult& tuning,
                                    const SessionOptions& options) {
  if (scene.trajectory.keyframes.empty())
    throw Error(scene.source_path + ": no trajectory: a scripted assembly needs one (or use a real device)");
  SessionResult out;
  out.coupling = coupling_for(scene, part2_mesh);
  out.limits = device_limits_for(scene);
  out.target = scene.assembled_pose.value_or(scene.trajectory.keyframes.back().pose);
  out.position_tolerance = scene.haptics.success_position.value_or(spacing);  // the descriptors' resolution
  out.angle_tolerance_deg = scene.haptics.success_angle_deg;

  engine.set_modes(tuning.chosen_modes);
  for (const QueryResult& r : engine.query_batch(gain_probe_poses(scene, spacing)))
    if (r.flags == query_ok) out.force_scale = std::max(out.force_scale, r.force.norm());
  out.geometry_gain = geometry_gain_for(scene, spacing, out.force_scale);

  LoopConfig config;
  config.rate_hz = scene.loop_rate_hz;
  const Trajectory& t = scene.trajectory;
  config.duration_s = options.duration_s.value_or(t.keyframes.back().time_s - t.keyframes.front().time_s +
                                                  scene.haptics.settle_s);
  config.budget_ms = scene.frame_budget_ms;
  config.coupling = out.coupling;
  config.geometry_gain = out.geometry_gain;
  config.modes.levels = loop_levels(tuning);
  const CostModel model = tuning.model;
  config.modes.predicted_ms = [model](std::size_t m) { return model.predict_ms(m); };
  config.keep_log = options.keep_log;

  ScriptedDevice device(t, out.limits, options.loop_back);
  BodyState part;
  part.pose = device.read(0).pose;  // the part starts in the user's hand
  WrenchEvaluator evaluator{[&engine](const Pose& p) { return engine.query(p); },
                            [&engine](std::size_t m) { engine.set_modes(m); }};
  const bool raise = (options.priority.nice_value != 0 || options.priority.realtime_priority > 0) && !options.simulated_time;
  if (raise) out.priority = raise_process_priority(options.priority);
  {
    // Warm-up at the loop's m' and the first pose, as a haptics program does before it
    // engages the device: the runtime's threads, now at their new priority, and the
    // caches see the query once before the first deadline.
    if (!options.simulated_time)
      for (int i = 0; i < options.warmup_queries; ++i) engine.query(part.pose);
    HapticLoopThread loop(device, evaluator, config, part,
                          options.simulated_time ? simulated_loop_clock() : steady_loop_clock());
    out.loop = loop.join();
  }
  if (raise) restore_process_priority(out.priority);
  out.final_error = pose_error(out.loop.final_part.pose, out.target);
  out.assembled = out.final_error.within(out.position_tolerance, out.angle_tolerance_deg);
  return out;
}

}  // namespace snapfit
