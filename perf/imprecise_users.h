#pragma once
// The imprecise users of the assembly benchmarks (perf/bench_assembly.cpp,
// perf/bench_real_cad.cpp): how a trial is drawn and played, how each frame's work is
// timed, and how the end is judged.
//
// Each trial (seeded) ends the device's target off the assembled pose by a lateral offset
// of 0-1 mm in a random direction and a tilt of 0-3 degrees about a random horizontal
// axis (none for translation-only), approaching from a random side (0-4 mm off the axis,
// 8-12 mm above the entry) over 1.5-3.5 s. The insertion is along -z of part 1's frame.
// Per trial: inserted (axial error <= the scene's position tolerance), success (inserted,
// lateral error <= tolerance + clearance, angle error <= tolerance + the fit's play
// atan(2 c / engaged)), the largest true interpenetration (mesh/interpenetration.h)
// every `stride` frames and at the last, force smoothness, and frame-work p99 and misses
// (frames whose query, with the rigid contact, took more CPU time than the budget).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>
#include <time.h>
#include <vector>

#include "core/quantile.h"
#include "engine/query/query_engine.h"
#include "mesh/interpenetration.h"
#include "mesh/mesh_distance.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/assembly_session.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/modes/mode_tuning.h"
#include "scheduler/haptics/rigid_contact.h"

namespace snapfit::bench {

// One insertion by the imprecise user.
struct UserTrial {
  double lateral = 0, lateral_dir = 0;  // mm, rad
  double tilt_deg = 0, tilt_dir = 0;    // degrees, rad (axis in the xy plane)
  double approach_offset = 0, approach_dir = 0, approach_height = 0;
  double duration_s = 0;
};

inline UserTrial draw_trial(std::mt19937& rng) {
  std::uniform_real_distribution<double> unit(0, 1);
  UserTrial t;
  t.lateral = unit(rng);
  t.lateral_dir = 2 * M_PI * unit(rng);
  t.tilt_deg = 3 * unit(rng);
  t.tilt_dir = 2 * M_PI * unit(rng);
  t.approach_offset = 4 * unit(rng);
  t.approach_dir = 2 * M_PI * unit(rng);
  t.approach_height = 8 + 4 * unit(rng);
  t.duration_s = 1.5 + 2 * unit(rng);
  return t;
}

// The trial's device trajectory: from above and to the side, to just above the entry
// (`entry` above the assembled pose, already offset and tilted), to the offset target.
inline Trajectory user_trajectory(const Pose& assembled, double entry, const UserTrial& t, bool tilt) {
  const Eigen::Vector3d offset(t.lateral * std::cos(t.lateral_dir), t.lateral * std::sin(t.lateral_dir), 0);
  Eigen::Quaterniond rotation = assembled.rotation;
  if (tilt)
    rotation =
        Eigen::AngleAxisd(t.tilt_deg * M_PI / 180, Eigen::Vector3d(std::cos(t.tilt_dir), std::sin(t.tilt_dir), 0)) *
        assembled.rotation;
  Keyframe start, above, end;
  start.pose.rotation = above.pose.rotation = end.pose.rotation = rotation;
  start.pose.translation = assembled.translation + offset +
                           Eigen::Vector3d(t.approach_offset * std::cos(t.approach_dir),
                                           t.approach_offset * std::sin(t.approach_dir), entry + t.approach_height);
  above.pose.translation = assembled.translation + offset + Eigen::Vector3d(0, 0, entry + 1);
  end.pose.translation = assembled.translation + offset;
  above.time_s = 0.4 * t.duration_s;
  end.time_s = t.duration_s;
  return Trajectory{{start, above, end}};
}

// What the judge needs of the fit.
struct Fit {
  double clearance = 0;  // radial, mm
  double entry = 0;      // part 2's travel from first reaching part 1 to the assembled pose
  double engaged = 0;    // length of the fit along the axis, for the play angle
};

struct TrialResult {
  bool inserted = false, success = false;
  double position_error = 0, lateral_error = 0, axial_error = 0, angle_error = 0;
  double max_penetration = 0, max_force_step = 0, force_hf_rms = 0, peak_force = 0;
  double frame_p99_ms = 0;             // the query's CPU time per frame
  double frame_wall_p99_ms = 0;        // the same on the wall clock
  std::size_t misses = 0, frames = 0;  // frames whose query's CPU time exceeded the budget
};

// Per-frame work of the method's query, on the wall clock and as the loop thread's CPU
// time (the loop runs on simulated time; on a loaded machine the wall clock also counts
// the time the thread waited for a core, the CPU time only its own work); the rigid
// contact's wall time is added to both (see timed_contact).
struct FrameWork {
  std::vector<double> wall_ms, cpu_ms;
};

inline double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return t.tv_sec + 1e-9 * t.tv_nsec;
}

template <class Query>
QueryResult timed_query(FrameWork& work, const Query& query) {
  const auto wall = std::chrono::steady_clock::now();
  const double cpu = thread_cpu_s();
  QueryResult q = query();
  work.cpu_ms.push_back(1e3 * (thread_cpu_s() - cpu));
  work.wall_ms.push_back(1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count());
  return q;
}

inline WrenchEvaluator timed(const WrenchEvaluator& inner, FrameWork& work) {
  WrenchEvaluator e = inner;
  e.evaluate = [inner, &work](const Pose& p) { return timed_query(work, [&] { return inner.evaluate(p); }); };
  if (inner.evaluate_state)
    e.evaluate_state = [inner, &work](const BodyState& s) {
      return timed_query(work, [&] { return inner.evaluate_state(s); });
    };
  return e;
}

// The rigid contact's time goes to the same frame's work as the engine's query (it
// runs right after it in the loop). It may run on helper threads
// (scheduler/haptics/parallel_contact.h) while the loop's thread waits: its wall time is what
// the frame spends on it, and counts in both.
inline std::function<ContactWrench(const Pose&)> timed_contact(std::function<ContactWrench(const Pose&)> inner,
                                                               FrameWork& work) {
  return [inner = std::move(inner), &work](const Pose& p) {
    const auto wall = std::chrono::steady_clock::now();
    ContactWrench c = inner(p);
    if (!work.cpu_ms.empty()) {
      const double ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
      work.cpu_ms.back() += ms;
      work.wall_ms.back() += ms;
    }
    return c;
  };
}

// One user's insertion with snapfit's engine at a fixed m' (at most the engine's), the
// scene's coupling and gain, and the rigid contact when `rigid` is given; simulated time.
// `in_region`: the loop's check that part 2 is inside the region part 1's fields cover
// (scheduler/haptics/haptic_setup.h region_guard; null: everywhere).
inline SessionResult run_engine_trial(const Scene& scene, const Mesh& part2, double spacing, QueryEngine& engine,
                                      const std::shared_ptr<const RigidContactModel>& rigid, long modes,
                                      FrameWork& work, std::function<bool(const Pose&)> in_region = nullptr) {
  SessionOptions options;
  options.simulated_time = true;
  const TuningResult fixed = pick_modes({TimingPoint{std::min<std::size_t>(modes, engine.max_modes()), 0, 0, 0, 1}},
                                        scene.frame_budget_ms, 0.25);
  double force_scale = 0;
  LoopConfig config = loop_config_for(scene, part2, spacing, engine, fixed, force_scale, rigid);
  config.in_region = std::move(in_region);
  if (config.contact) config.contact = timed_contact(config.contact, work);
  return run_scripted_session(scene, part2, spacing, config, timed(wrench_evaluator(engine), work), options);
}

// Judges one trial (see the top of the file).
inline TrialResult measure(const Fit& fit, double frame_budget_ms, const SessionResult& run, const FrameWork& work,
                           const Mesh& m1, const MeshDistanceIndex& i1, const Mesh& m2, const MeshDistanceIndex& i2,
                           std::size_t stride) {
  TrialResult r;
  const LoopReport& loop = run.loop;
  const Pose& final_pose = loop.final_part.pose;
  const Eigen::Vector3d d = final_pose.translation - run.target.translation;
  r.position_error = run.final_error.position;
  r.angle_error = run.final_error.angle_deg;
  r.axial_error = std::abs(d.z());
  r.lateral_error = std::hypot(d.x(), d.y());
  const double play_deg = std::atan(2 * fit.clearance / fit.engaged) * 180 / M_PI;
  r.inserted = r.axial_error <= run.position_tolerance;
  r.success = r.inserted && r.lateral_error <= run.position_tolerance + fit.clearance &&
              r.angle_error <= run.angle_tolerance_deg + play_deg;
  for (std::size_t i = 0; i < loop.log.size(); ++i) {
    const FrameRecord& f = loop.log[i];
    r.peak_force = std::max(r.peak_force, f.sent.force.norm());
    if (i > 0) r.max_force_step = std::max(r.max_force_step, (f.sent.force - loop.log[i - 1].sent.force).norm());
    if (i > 0 && i + 1 < loop.log.size())
      r.force_hf_rms += (loop.log[i + 1].sent.force - 2 * f.sent.force + loop.log[i - 1].sent.force).squaredNorm();
    if (i % stride == 0) r.max_penetration = std::max(r.max_penetration, deepest_interpenetration(f.part, m1, i1, m2, i2));
  }
  if (loop.log.size() > 2) r.force_hf_rms = std::sqrt(r.force_hf_rms / (loop.log.size() - 2));
  r.max_penetration = std::max(r.max_penetration, deepest_interpenetration(final_pose, m1, i1, m2, i2));
  r.frames = loop.frames;
  r.frame_p99_ms = quantile(work.cpu_ms, 0.99);
  r.frame_wall_p99_ms = quantile(work.wall_ms, 0.99);
  for (double w : work.cpu_ms) r.misses += w > frame_budget_ms;
  return r;
}

}  // namespace snapfit::bench
