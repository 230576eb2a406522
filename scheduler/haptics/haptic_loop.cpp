#include "snapfit/haptic_loop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <deque>
#include <exception>
#include <future>
#include <memory>
#include <optional>
#include <thread>

#include "core/quantile.h"
#include "core/subnormal_flush.h"
#include "core/thread_name.h"
#include "scheduler/haptics/force_rate_limit.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "scheduler/haptics/wrench_trust.h"
#include "snapfit/error.h"

namespace snapfit {

const char* loop_wait_name(LoopWait wait) { return wait == LoopWait::spin ? "spin" : "sleep"; }

LoopWait parse_loop_wait(const std::string& name) {
  if (name == "spin") return LoopWait::spin;
  if (name == "sleep") return LoopWait::sleep;
  throw Error("loop wait '" + name + "': expected spin or sleep");
}

LoopClock steady_loop_clock(LoopWait wait) {
  using Clock = std::chrono::steady_clock;
  const auto origin = Clock::now();
  LoopClock c;
  c.now = [origin] { return std::chrono::duration<double>(Clock::now() - origin).count(); };
  c.wait_until = [origin, wait](double t) {
    const auto deadline = origin + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(t));
    if (wait == LoopWait::sleep) {
      // Sleep through most of the wait (the OS wakes us late by up to ~0.1 ms), spin the rest.
      const auto wake = deadline - std::chrono::microseconds(200);
      if (Clock::now() < wake) std::this_thread::sleep_until(wake);
      while (Clock::now() < deadline) std::this_thread::yield();
      return;
    }
    while (Clock::now() < deadline) {
    }
  };
  return c;
}

LoopClock simulated_loop_clock() {
  auto t = std::make_shared<double>(0.0);
  return LoopClock{[t] { return *t; }, [t](double until) { *t = std::max(*t, until); }};
}

namespace {

// The force-rate slew's energy tank holds at most this much of the energy the bound's
// damping removed (J): about what a 0.2 N offset does over 5 mm of hand travel, so
// energy stored long ago is not handed back in one go.
constexpr double kSlewTankCapacityJ = 1e-3;

bool finite_state(const BodyState& s) {
  return s.pose.is_finite() && s.velocity.allFinite() && s.angular_velocity.allFinite() &&
         std::abs(s.pose.rotation.norm() - 1.0) < 1e-3;
}

void check_config(const LoopConfig& c) {
  if (!(std::isfinite(c.rate_hz) && c.rate_hz > 0)) throw Error("haptic loop: rate must be > 0 Hz");
  if (!(std::isfinite(c.budget_ms) && c.budget_ms > 0)) throw Error("haptic loop: frame budget must be > 0 ms");
  if (!(std::isfinite(c.geometry_gain) && c.geometry_gain >= 0)) throw Error("haptic loop: geometry gain must be >= 0");
  if (!std::isfinite(c.duration_s)) throw Error("haptic loop: duration must be finite");
  if (c.duration_s <= 0 && !c.stop) throw Error("haptic loop: no duration and no stop flag: it would never end");
  if (!(std::isfinite(c.max_travel) && c.max_travel >= 0 && std::isfinite(c.max_rotation) && c.max_rotation >= 0))
    throw Error("haptic loop: the speed limits must be >= 0");
  if (!(std::isfinite(c.max_force_rate_n_per_s) && c.max_force_rate_n_per_s >= 0))
    throw Error("haptic loop: the force-rate bound must be >= 0 N/s");
  if (c.modes.levels.empty()) throw Error("haptic loop: the m' ladder is empty");
  if (!std::is_sorted(c.modes.levels.begin(), c.modes.levels.end()) || c.modes.levels.front() == 0)
    throw Error("haptic loop: the m' ladder must be positive and increasing");
}

// Tracks misses and frame times and decides when m' steps down or up (see the header).
class ModeGovernor {
 public:
  ModeGovernor(const ModePolicy& p, double budget_ms) : p_(p), budget_ms_(budget_ms), level_(p.levels.size() - 1) {}
  std::size_t modes() const { return p_.levels[level_]; }

  // After each frame, with its own work time (wake-up to wrench sent) and whether it
  // missed because of that work. Returns the new m' when it changes, 0 otherwise;
  // `reason` says why.
  std::size_t after_frame(std::size_t frame, double frame_ms, bool missed, bool stall, std::string& reason) {
    if (stall) stalls_.push_back(frame);
    while (!stalls_.empty() && stalls_.front() + p_.miss_window <= frame) stalls_.pop_front();
    // Stalls filling more than half the window: not stalls, a slower machine.
    if (stall && 2 * stalls_.size() > p_.miss_window) missed = true;
    if (missed) misses_.push_back(frame);
    while (!misses_.empty() && misses_.front() + p_.miss_window <= frame) misses_.pop_front();
    recent_.push_back(frame_ms);
    if (recent_.size() > p_.up_after_frames) recent_.pop_front();
    ++since_change_;
    if (missed || stall) since_change_ = 0, recent_.clear();

    if (misses_.size() >= p_.misses_to_step_down && level_ > 0) {
      reason = std::to_string(misses_.size()) + " misses in the last " + std::to_string(p_.miss_window) + " frames";
      return change(level_ - 1);
    }
    // Step-up is judged once per miss window, not every frame: the p99 of the recent
    // frames is a sort of up_after_frames values, too much for the per-frame path.
    if (level_ + 1 < p_.levels.size() && since_change_ >= p_.up_after_frames && recent_.size() >= p_.up_after_frames &&
        since_change_ % std::max<std::size_t>(1, p_.miss_window) == 0) {
      const double p99 = quantile(std::vector<double>(recent_.begin(), recent_.end()), 0.99);
      const std::size_t next = p_.levels[level_ + 1];
      const double ratio = p_.predicted_ms ? p_.predicted_ms(next) / std::max(1e-9, p_.predicted_ms(modes()))
                                           : double(next) / double(modes());
      if (p99 * ratio <= p_.up_headroom * budget_ms_) {
        reason = "headroom: p99 " + std::to_string(p99) + " ms over the last " + std::to_string(recent_.size()) +
                 " frames, predicted " + std::to_string(p99 * ratio) + " ms at the next level";
        return change(level_ + 1);
      }
    }
    return 0;
  }

 private:
  std::size_t change(std::size_t level) {
    level_ = level;
    misses_.clear();
    recent_.clear();
    since_change_ = 0;
    return modes();
  }
  const ModePolicy& p_;
  double budget_ms_;
  std::size_t level_;
  std::deque<std::size_t> misses_, stalls_;
  std::deque<double> recent_;
  std::size_t since_change_ = 0;
};

// The passivity measures on the geometric wrench (see the header): its stiffness along
// the motion, for the implicit step, and the passivity observer and damping controller.
class PassivityController {
 public:
  explicit PassivityController(const LoopConfig& c) : config_(c) {}

  // Called each frame after the query at the part's pose, with the wrench it renders
  // (the engine's times `trust`): observes the last step (energy created) and updates the
  // stiffness estimate. The held wrench derives from the potential times the trust it was
  // rendered with, so the step is judged against that potential at both ends.
  void observe(const Pose& pose, const QueryResult& q, const Wrench& wrench, double trust) {
    const bool ok = q.flags == query_ok;
    const double u = config_.coupling.metres_per_unit;
    const double potential = ok ? config_.geometry_gain * u * q.energy : 0.0;
    stiffness_ *= kDecay;
    rot_stiffness_ *= kDecay;
    if (valid_ && ok && q.modes == modes_) {
      const Eigen::Vector3d dx = u * (pose.translation - pose_.translation);
      const Eigen::Vector3d dtheta = rotation_between(pose_.rotation, pose.rotation);
      const double work = wrench_.force.dot(dx) + wrench_.torque.dot(dtheta);
      const double created = work - trust_ * (potential_ - potential);
      if (std::isfinite(created)) budget_ = std::min(0.0, budget_ + (-created));
      // Secant stiffness along the motion, -dF.dx / |dx|^2 (only its positive part
      // threatens stability); steps below a nanometre / nanoradian are float noise.
      if (dx.norm() > 1e-9) {
        const double k = -(wrench.force - wrench_.force).dot(dx) / dx.squaredNorm();
        if (std::isfinite(k)) stiffness_ = std::max(stiffness_, k);
      }
      if (dtheta.norm() > 1e-9) {
        const double k = -(wrench.torque - wrench_.torque).dot(dtheta) / dtheta.squaredNorm();
        if (std::isfinite(k)) rot_stiffness_ = std::max(rot_stiffness_, k);
      }
    }
    valid_ = ok;
    pose_ = pose;
    potential_ = potential;
    trust_ = trust;
    modes_ = q.modes;
    wrench_ = wrench;
  }

  // The implicit extras for this frame's step: the geometric stiffness, and damping
  // that removes the energy still owed.
  ImplicitExtras extras(const BodyState& part) const {
    ImplicitExtras d;
    if (!config_.passivity_control) return d;
    d.stiffness = stiffness_;
    d.rot_stiffness = rot_stiffness_;
    if (budget_ >= 0) return d;
    const double u = config_.coupling.metres_per_unit;
    const double twice_kinetic = config_.coupling.mass_kg * (u * part.velocity).squaredNorm() +
                                 config_.coupling.inertia_kg_m2 * part.angular_velocity.squaredNorm();
    const double period = 1.0 / config_.rate_hz;
    if (!(twice_kinetic > 0)) return d;
    // Dissipated power alpha * 2 KE over one step removes the deficit; alpha dt <= 10.
    const double alpha = std::min(-budget_ / (period * twice_kinetic), 10.0 / period);
    d.damping = alpha * config_.coupling.mass_kg;
    d.rot_damping = alpha * config_.coupling.inertia_kg_m2;
    return d;
  }

  // After the step: the energy the extra damping removed (its force times the new
  // velocity over the step). Returns it.
  double stepped(const BodyState& part, const ImplicitExtras& d) {
    if (d.damping == 0 && d.rot_damping == 0) return 0;
    const double u = config_.coupling.metres_per_unit;
    const double period = 1.0 / config_.rate_hz;
    const double removed =
        period * (d.damping * (u * part.velocity).squaredNorm() + d.rot_damping * part.angular_velocity.squaredNorm());
    budget_ = std::min(0.0, budget_ + removed);
    return removed;
  }

  void invalidate() { valid_ = false; }

 private:
  static constexpr double kDecay = 0.995;  // the stiffness estimate's memory: ~200 frames
  const LoopConfig& config_;
  bool valid_ = false;
  Pose pose_;
  double potential_ = 0;  // the engine's, times the gain (J), before the trust
  double trust_ = 1;      // the share of it the held wrench renders
  std::size_t modes_ = 0;
  Wrench wrench_;
  double budget_ = 0;                         // <= 0: energy created by the steps and not yet removed, J
  double stiffness_ = 0, rot_stiffness_ = 0;  // N / m, N m / rad
};

// The speed limit (LoopConfig::max_travel, max_rotation): scales the step's velocities
// down so that the part moves and turns at most that far from `before`.
void limit_speed(BodyState& part, const Pose& before, const LoopConfig& c, double period) {
  if (c.max_travel > 0 && part.velocity.norm() * period > c.max_travel) {
    part.velocity *= c.max_travel / (part.velocity.norm() * period);
    part.pose.translation = before.translation + period * part.velocity;
  }
  if (c.max_rotation > 0 && part.angular_velocity.norm() * period > c.max_rotation) {
    part.angular_velocity *= c.max_rotation / (part.angular_velocity.norm() * period);
    part.pose.rotation = (rotation_exp(period * part.angular_velocity) * before.rotation).normalized();
  }
}

// What the loop carries from frame to frame.
struct LoopState {
  explicit LoopState(const LoopConfig& config) : governor(config.modes, config.budget_ms), passivity(config) {
    slew.capacity_j = kSlewTankCapacityJ;
  }
  ModeGovernor governor;
  PassivityController passivity;
  Wrench geometric, external;  // the engine's wrench as rendered; with the contact, held over missed ticks
  double trust = 1;            // the share of the engine's wrench rendered this frame
  ContactWrench contact;
  ImplicitExtras extra;
  std::optional<BodyState> last_good_handle;
  std::optional<Eigen::Vector3d> last_coupling_force;  // the coupling's force on the part last frame
  SentForceSlew slew;
};

// 1. The device's pose. A non-finite reading is replaced by the last good one: a NaN
// must not reach the simulation or the hand.
BodyState read_handle(HapticDevice& device, double tick_time, const BodyState& part, LoopState& s,
                      LoopReport& report) {
  BodyState handle = device.read(tick_time);
  if (!finite_state(handle)) {
    ++report.bad_device_reads;
    handle = s.last_good_handle ? *s.last_good_handle : part;
  }
  s.last_good_handle = handle;
  return handle;
}

// 2. The geometric wrench at the part's pose (with the loop's gain, torque in N m), as
// far as its error estimate vouches for it (s.trust), and the estimate; the rigid
// contact's beside it.
ErrorEstimate geometric_wrench(const QueryResult& q, const Pose& queried, const LoopConfig& config, LoopState& s,
                               LoopReport& report) {
  s.geometric = Wrench{};
  s.trust = 0;
  ErrorEstimate error;
  if (q.flags == query_ok) {
    s.geometric.force = config.geometry_gain * q.force;
    s.geometric.torque = config.geometry_gain * config.coupling.metres_per_unit * q.torque;
    error = {q.error_estimate.energy, config.geometry_gain * q.error_estimate.force,
             config.geometry_gain * config.coupling.metres_per_unit * q.error_estimate.torque};
    s.trust = wrench_trust(s.geometric, error, config.trust);
    if (config.in_region && !config.in_region(queried)) {
      s.trust = 0;  // part 1's fields do not cover where part 2 is: nothing to vouch for
      ++report.out_of_region_frames;
    }
    s.geometric.force *= s.trust;
    s.geometric.torque *= s.trust;
    if (s.trust < 1) ++(s.trust > 0 ? report.trust_scaled_frames : report.trust_withheld_frames);
  } else {
    ++report.flagged_frames;
  }
  // Rigid contact: its own potential and exact stiffness, so it is integrated
  // implicitly and left out of the observer (which checks the explicit wrench).
  if (config.contact) s.contact = config.contact(queried);
  s.external.force = s.geometric.force + s.contact.wrench.force;
  s.external.torque = s.geometric.torque + s.contact.wrench.torque;
  return error;
}

// 3. One fixed step of the part (with the passivity controller's damping, and the
// force-rate bound's where the coupling's force would change faster than it allows).
// Returns the energy the rate bound's damping removed, J.
double step_part(BodyState& part, const BodyState& handle, const Pose& queried, const QueryResult& q,
                 const LoopConfig& config, double period, LoopState& s, LoopReport& report) {
  s.passivity.observe(part.pose, q, s.geometric, s.trust);
  s.extra = s.passivity.extras(part);
  s.extra.contact_stiffness = s.contact.stiffness;
  ImplicitExtras stepped = s.extra;
  const BodyState before_step = part;
  step_body(part, handle, s.external, config.coupling, period, stepped);
  const double max_change = config.max_force_rate_n_per_s * period;
  if (max_change > 0 && s.last_coupling_force &&
      (coupling_wrench(part, handle, config.coupling).force - *s.last_coupling_force).norm() > max_change) {
    if (const double beta = rate_limiting_damping(before_step, handle, s.external, config.coupling, period, s.extra,
                                                  *s.last_coupling_force, max_change);
        beta > 0) {
      stepped.damping += beta;
      part = before_step;
      step_body(part, handle, s.external, config.coupling, period, stepped);
    }
  }
  limit_speed(part, queried, config, period);
  double rate_dissipated_j = 0;
  if (const double beta = stepped.damping - s.extra.damping; beta > 0) {
    ++report.rate_limited_frames;
    rate_dissipated_j = period * beta * (config.coupling.metres_per_unit * part.velocity).squaredNorm();
    report.rate_limit_dissipated_j += rate_dissipated_j;
  }
  if (const double removed = s.passivity.stepped(part, s.extra); removed > 0) {
    ++report.passivity_frames;
    report.passivity_dissipated_j += removed;
  }
  if (!finite_state(part)) {  // cannot happen with finite inputs; never propagate it
    ++report.part_resets;
    part = handle;
    s.passivity.invalidate();
  }
  return rate_dissipated_j;
}

// 4. The coupling's reaction to the device: slewed within the force-rate bound, clamped
// to the device's limits.
Wrench sent_wrench(const BodyState& part, const BodyState& handle, const LoopConfig& config, double period,
                   const DeviceLimits& limits, double rate_dissipated_j, LoopState& s) {
  const double max_change = config.max_force_rate_n_per_s * period;
  const Wrench on_part = coupling_wrench(part, handle, config.coupling);
  s.last_coupling_force = on_part.force;
  const Eigen::Vector3d reaction =
      max_change > 0 ? slewed_sent_force(s.slew, -on_part.force, config.coupling.metres_per_unit * handle.pose.translation,
                                         max_change, rate_dissipated_j)
                     : Eigen::Vector3d(-on_part.force);
  return clamp_to_limits(Wrench{reaction, -on_part.torque}, limits);
}

// A frame that ended after its deadline: late because the thread woke late, or because
// its work did not fit (a stall when far beyond the cost model's prediction).
struct FrameTiming {
  bool missed = false, compute_miss = false, stall = false;
};

// `work_ms` is the loop thread's own work in this tick: the frame's (wake-up to wrench
// sent) plus `carried_ms`, the previous frame's tail (its callbacks, the governor) that
// ran past this tick, so that the thread never slept.
FrameTiming frame_timing(double end, double tick_time, double work_ms, double carried_ms, double period,
                         const LoopConfig& config, const ModeGovernor& governor, LoopReport& report) {
  FrameTiming t;
  t.missed = end > tick_time + period;
  // A miss whose work fit in the headroom share of the budget came from waking late
  // (the OS), which a smaller m' cannot fix: it is counted, not acted on.
  t.compute_miss = t.missed && work_ms > config.modes.up_headroom * config.budget_ms;
  if (t.missed && !t.compute_miss) ++report.late_wakeup_misses;
  // Only a work-bound miss asks the cost model (not every frame). The model predicts
  // the query, so a stall is judged on the frame's own work, not the carried tail.
  if (t.compute_miss && config.modes.stall_factor > 0 && config.modes.predicted_ms) {
    const double predicted = config.modes.predicted_ms(governor.modes());
    t.stall = predicted > 0 && work_ms - carried_ms > config.modes.stall_factor * predicted;
  }
  if (t.stall) ++report.stall_misses;
  return t;
}

// No catch-up after a miss: the next frame runs at the first tick still ahead; the part
// moves over the ticks that passed with the held wrench. Returns that tick.
std::size_t hold_over_missed_ticks(std::size_t tick, double end, BodyState& part, HapticDevice& device,
                                   const LoopConfig& config, double period, LoopState& s, LoopReport& report) {
  const std::size_t next = static_cast<std::size_t>(std::floor(end / period)) + 1;
  for (std::size_t t = tick + 1; t < next; ++t) {
    if (config.duration_s > 0 && t * period >= config.duration_s - 1e-12) break;
    const Pose before = part.pose;
    ImplicitExtras held;
    held.contact_stiffness = s.contact.stiffness;
    step_body(part, device.read(t * period), s.external, config.coupling, period, held);
    limit_speed(part, before, config, period);
    ++report.skipped_ticks;
    s.passivity.invalidate();
  }
  return next;
}

// The report's counts after a frame (or at the end), so that on_frame sees them whole:
// ticks, elapsed time, the slew's totals, the part and m' now.
void count_so_far(LoopReport& report, const LoopState& s, const BodyState& part, double elapsed_s) {
  report.ticks = report.frames + report.skipped_ticks;
  report.elapsed_s = elapsed_s;
  report.rate_slewed_frames = s.slew.slewed_frames;
  report.rate_slew_work_j = s.slew.spent_j;
  report.measured_rate_hz = elapsed_s > 0 ? report.frames / elapsed_s : 0;
  report.final_part = part;
  report.final_modes = s.governor.modes();
}

}  // namespace

WrenchEvaluator wrench_evaluator(QueryEngine& engine) {
  WrenchEvaluator e;
  e.evaluate = [&engine](const Pose& p) { return engine.query(p); };
  e.set_modes = [&engine](std::size_t m) { engine.request_modes(m); };  // never waits for a product
  return e;
}

LoopReport run_haptic_loop(HapticDevice& device, const WrenchEvaluator& engine, const LoopConfig& config,
                           const LoopClock& clock, BodyState part) {
  check_config(config);
  // A part at rest at its fit has pose offsets that turn subnormal in single precision,
  // which would make every frame several times slower (core/subnormal_flush.h).
  const SubnormalFlush flush;
  const double period = 1.0 / config.rate_hz;
  const DeviceLimits limits = device.limits();
  LoopState s(config);
  if (engine.set_modes) engine.set_modes(s.governor.modes());

  LoopReport report;
  report.rate_hz = config.rate_hz;
  report.final_part = part;
  report.final_modes = s.governor.modes();
  const std::size_t expected = config.duration_s > 0 ? static_cast<std::size_t>(config.duration_s * config.rate_hz) : 0;
  if (config.keep_frame_times) report.frame_ms.reserve(expected), report.wake_late_ms.reserve(expected);
  if (config.keep_log) report.log.reserve(expected);

  std::size_t tick = 0, frame = 0;
  const double start = clock.now();
  while (true) {
    const double tick_time = tick * period;  // loop time of this tick
    if (config.duration_s > 0 && tick_time >= config.duration_s - 1e-12) break;
    if (config.stop && config.stop->load()) break;
    const double ready = clock.now() - start;  // the previous frame's tail done
    clock.wait_until(start + tick_time);
    const double woke = clock.now() - start;  // later than the tick when the OS wakes us late
    if (config.replace_part && config.replace_part(part)) {
      s.passivity.invalidate();  // the step from the last pose to this one was not the part's motion
      s.last_coupling_force.reset();
    }

    const BodyState handle = read_handle(device, tick_time, part, s, report);
    const Pose queried = part.pose;
    const QueryResult q = engine.evaluate_state ? engine.evaluate_state(part) : engine.evaluate(queried);
    const ErrorEstimate geometric_error = geometric_wrench(q, queried, config, s, report);
    const double rate_dissipated_j = step_part(part, handle, queried, q, config, period, s, report);
    const Wrench sent = sent_wrench(part, handle, config, period, limits, rate_dissipated_j, s);
    device.send(sent, tick_time);

    const double end = clock.now() - start;
    const double frame_ms = 1e3 * (end - tick_time);
    const double carried_ms = 1e3 * std::max(0.0, ready - tick_time);
    const double compute_ms = 1e3 * (end - woke) + carried_ms;
    const FrameTiming timing = frame_timing(end, tick_time, compute_ms, carried_ms, period, config, s.governor, report);
    const double wake_late_ms = 1e3 * (woke - std::max(ready, tick_time));
    if (config.keep_frame_times) report.frame_ms.push_back(frame_ms), report.wake_late_ms.push_back(wake_late_ms);
    ++report.frames;
    if (timing.missed) ++report.misses;
    const std::size_t next =
        timing.missed ? hold_over_missed_ticks(tick, end, part, device, config, period, s, report) : tick + 1;

    std::string reason;
    const std::size_t before = s.governor.modes();
    if (const std::size_t m =
            s.governor.after_frame(frame, compute_ms, timing.compute_miss && !timing.stall, timing.stall, reason)) {
      report.mode_changes.push_back(ModeChange{tick_time, frame, before, m, reason});
      if (engine.set_modes) engine.set_modes(m);
    }
    count_so_far(report, s, part, end);
    if (config.keep_log || config.on_frame) {
      const FrameRecord record{tick_time,   frame_ms,         handle.pose,     queried,         q.energy,
                               s.geometric, s.contact.wrench, s.contact.depth, geometric_error, sent,
                               q.modes,     q.flags,          timing.missed,   q.constraint,    q.constraint_weight,
                               s.trust,     wake_late_ms};
      if (config.keep_log) report.log.push_back(record);
      if (config.on_frame) config.on_frame(record, report);
    }
    ++frame;
    tick = next;
  }
  count_so_far(report, s, part, clock.now() - start);
  return report;
}

LoopCounts counts_between(const LoopCounts& a, const LoopCounts& b) {
  LoopCounts d = b;
  d.elapsed_s = b.elapsed_s - a.elapsed_s;
  d.ticks = b.ticks - a.ticks;
  d.frames = b.frames - a.frames;
  d.misses = b.misses - a.misses;
  d.skipped_ticks = b.skipped_ticks - a.skipped_ticks;
  d.flagged_frames = b.flagged_frames - a.flagged_frames;
  d.trust_scaled_frames = b.trust_scaled_frames - a.trust_scaled_frames;
  d.trust_withheld_frames = b.trust_withheld_frames - a.trust_withheld_frames;
  d.out_of_region_frames = b.out_of_region_frames - a.out_of_region_frames;
  d.bad_device_reads = b.bad_device_reads - a.bad_device_reads;
  d.part_resets = b.part_resets - a.part_resets;
  d.passivity_frames = b.passivity_frames - a.passivity_frames;
  d.passivity_dissipated_j = b.passivity_dissipated_j - a.passivity_dissipated_j;
  d.rate_limited_frames = b.rate_limited_frames - a.rate_limited_frames;
  d.rate_limit_dissipated_j = b.rate_limit_dissipated_j - a.rate_limit_dissipated_j;
  d.rate_slewed_frames = b.rate_slewed_frames - a.rate_slewed_frames;
  d.rate_slew_work_j = b.rate_slew_work_j - a.rate_slew_work_j;
  d.late_wakeup_misses = b.late_wakeup_misses - a.late_wakeup_misses;
  d.stall_misses = b.stall_misses - a.stall_misses;
  d.measured_rate_hz = d.elapsed_s > 0 ? d.frames / d.elapsed_s : 0;
  return d;
}

struct HapticLoopThread::State {
  std::future<LoopReport> result;
};

HapticLoopThread::HapticLoopThread(HapticDevice& device, WrenchEvaluator engine, LoopConfig config, BodyState part,
                                   LoopClock clock)
    : state_(std::make_unique<State>()) {
  config.stop = &stop_;
  state_->result =
      std::async(std::launch::async, [&device, engine = std::move(engine), config, part, clock = std::move(clock)] {
        name_this_thread("snapfit-loop");
        return run_haptic_loop(device, engine, config, clock, part);
      });
}

HapticLoopThread::~HapticLoopThread() {
  stop_ = true;
  if (state_ && state_->result.valid()) state_->result.wait();
}

LoopReport HapticLoopThread::join() { return state_->result.get(); }

}  // namespace snapfit
