// The haptic loop (snapfit/haptic_loop.h) on a manual clock with injected frame
// costs: rate, miss counting without catch-up, stepping m' down and up; then on the
// real clock with a cheap evaluator; then a scripted device pulling the part home.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <map>

#include "scheduler/haptics/scripted_device.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "snapfit/error.h"
#include "snapfit/haptic_loop.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

// Loop time that only moves when the loop waits or the evaluator "computes".
struct ManualClock {
  double t = 0;
  LoopClock clock() {
    return LoopClock{[this] { return t; }, [this](double until) { t = std::max(t, until); }};
  }
};

// A device that holds one pose.
struct FixedDevice : HapticDevice {
  BodyState state;
  std::size_t sent = 0;
  BodyState read(double) override { return state; }
  void send(const Wrench&, double) override { ++sent; }
  DeviceLimits limits() const override { return {}; }
};

// Costs ms per query: `base_ms_per_1k` per 1000 modes, plus `extra` at given query numbers.
struct CostedEvaluator {
  ManualClock* clock;
  double base_ms_per_1k = 0.02;
  std::map<std::size_t, double> extra;  // query index -> added ms
  std::size_t modes = 0, calls = 0;
  std::vector<std::size_t> set_calls;
  WrenchEvaluator evaluator() {
    return WrenchEvaluator{[this](const Pose&) {
                             double ms = base_ms_per_1k * modes / 1000.0;
                             if (auto it = extra.find(calls); it != extra.end()) ms += it->second;
                             ++calls;
                             clock->t += ms * 1e-3;
                             QueryResult r;
                             r.modes = modes;
                             return r;
                           },
                           [this](std::size_t m) {
                             modes = m;
                             set_calls.push_back(m);
                           }};
  }
};

LoopConfig config(double duration_s) {
  LoopConfig c;
  c.rate_hz = 1000;
  c.duration_s = duration_s;
  c.budget_ms = 1.0;
  c.coupling = make_coupling(1e-3, 0.05, 2e-6, 800, 0.05, 1.0);
  c.geometry_gain = 0;
  c.modes.levels = {4096, 8192, 16384};
  c.modes.up_after_frames = 500;
  return c;
}

}  // namespace

TEST_CASE("haptic loop: a cheap evaluator keeps the rate, every tick runs, no misses") {
  ManualClock clock;
  FixedDevice device;
  CostedEvaluator engine{&clock};
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), config(2.0), clock.clock(), BodyState{});
  CHECK(r.ticks == 2000);
  CHECK(r.frames == 2000);
  CHECK(r.misses == 0);
  CHECK(r.skipped_ticks == 0);
  CHECK(device.sent == 2000);
  CHECK(r.mode_changes.empty());
  CHECK(engine.set_calls == std::vector<std::size_t>{16384});  // starts at the tuned m'
  CHECK(r.measured_rate_hz == doctest::Approx(1000).epsilon(1e-3));
  // Frame times: 16.384 x 0.02 ms per frame, to round-off.
  for (double ms : r.frame_ms) CHECK(ms == doctest::Approx(0.32768).epsilon(1e-6));
  REQUIRE(r.log.size() == 2000);
  CHECK(r.log[1234].time_s == doctest::Approx(1.234));
}

TEST_CASE("haptic loop: an overrun is a miss, holds the last wrench and is not caught up with a burst") {
  ManualClock clock;
  FixedDevice device;
  CostedEvaluator engine{&clock};
  engine.extra[100] = 2.5;  // frame 100 takes ~2.8 ms: ends after ticks 101 and 102
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), config(1.0), clock.clock(), BodyState{});
  CHECK(r.misses == 1);
  CHECK(r.skipped_ticks == 2);
  CHECK(r.frames == 998);
  CHECK(r.ticks == 1000);
  // The frame after the miss runs at tick 103 (the first tick still ahead), not at once.
  CHECK(r.log[100].missed);
  CHECK(r.log[101].time_s == doctest::Approx(0.103));
  CHECK(r.log[101].frame_ms == doctest::Approx(0.32768).epsilon(1e-6));
  CHECK(r.mode_changes.empty());  // one miss is not a repeat
}

TEST_CASE("haptic loop: repeated misses step m' down at once, and headroom steps it back up, one level at a time") {
  ManualClock clock;
  FixedDevice device;
  CostedEvaluator engine{&clock};
  engine.extra[200] = 1.0;
  engine.extra[240] = 1.0;  // second miss within 100 frames
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), config(3.0), clock.clock(), BodyState{});
  CHECK(r.misses == 2);
  REQUIRE(r.mode_changes.size() >= 2);
  CHECK(r.mode_changes[0].from == 16384);
  CHECK(r.mode_changes[0].to == 8192);
  CHECK(r.mode_changes[0].frame == 240);  // right after the second miss
  CHECK(r.mode_changes[0].reason.find("misses") != std::string::npos);
  // 500 clean frames later, p99 0.164 ms x 2 fits 0.6 ms: back to 16384.
  CHECK(r.mode_changes[1].from == 8192);
  CHECK(r.mode_changes[1].to == 16384);
  CHECK(r.mode_changes[1].frame >= 240 + 500);
  CHECK(r.mode_changes[1].reason.find("headroom") != std::string::npos);
  CHECK(r.mode_changes.size() == 2);  // never above the tuned m'
  CHECK(r.final_modes == 16384);
  CHECK(engine.set_calls == std::vector<std::size_t>{16384, 8192, 16384});
}

TEST_CASE("haptic loop: without headroom m' stays down") {
  ManualClock clock;
  FixedDevice device;
  CostedEvaluator engine{&clock};
  engine.base_ms_per_1k = 0.05;  // 0.41 ms at 8192: x2 = 0.82 ms > 0.6 ms of the budget
  engine.extra[10] = 1.0;
  engine.extra[20] = 1.0;
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), config(2.0), clock.clock(), BodyState{});
  REQUIRE(r.mode_changes.size() == 1);
  CHECK(r.mode_changes[0].to == 8192);
  CHECK(r.final_modes == 8192);
}

TEST_CASE("haptic loop: invalid configurations are refused with a reason") {
  ManualClock clock;
  FixedDevice device;
  CostedEvaluator engine{&clock};
  LoopConfig c = config(1.0);
  c.modes.levels.clear();
  CHECK_THROWS_WITH_AS(run_haptic_loop(device, engine.evaluator(), c, clock.clock(), BodyState{}),
                       doctest::Contains("ladder"), Error);
  c = config(1.0);
  c.rate_hz = NAN;
  CHECK_THROWS_AS(run_haptic_loop(device, engine.evaluator(), c, clock.clock(), BodyState{}), Error);
  c = config(0.0);
  CHECK_THROWS_WITH_AS(run_haptic_loop(device, engine.evaluator(), c, clock.clock(), BodyState{}),
                       doctest::Contains("never end"), Error);
}

TEST_CASE("haptic loop: the steady clock's waits, spinning and sleeping, return at or after the deadline") {
  for (const LoopWait wait : {LoopWait::spin, LoopWait::sleep}) {
    CAPTURE(loop_wait_name(wait));
    const LoopClock clock = steady_loop_clock(wait);
    for (const double ahead : {0.0, 0.0001, 0.003}) {
      const double deadline = clock.now() + ahead;
      clock.wait_until(deadline);
      CHECK(clock.now() >= deadline);
    }
    clock.wait_until(clock.now() - 1.0);  // a deadline already passed returns at once
    CHECK(parse_loop_wait(loop_wait_name(wait)) == wait);
  }
  CHECK_THROWS_WITH_AS(parse_loop_wait("busy"), doctest::Contains("expected spin or sleep"), Error);
}

TEST_CASE("haptic loop: on the real clock, on its own thread, ticks follow absolute deadlines, spinning or sleeping") {
  for (const LoopWait wait : {LoopWait::spin, LoopWait::sleep}) {
    CAPTURE(loop_wait_name(wait));
    FixedDevice device;
    std::size_t calls = 0;
    WrenchEvaluator cheap{[&calls](const Pose&) {
                            ++calls;
                            return QueryResult{};
                          },
                          nullptr};
    HapticLoopThread loop(device, cheap, config(0.5), BodyState{}, steady_loop_clock(wait));
    const LoopReport r = loop.join();
    // Absolute deadlines: exactly 500 ticks in 0.5 s, however late the thread wakes on a
    // loaded machine (late frames are misses; how rare they are is measured by
    // perf/bench_haptic_loop, not asserted here).
    CHECK(r.ticks == 500);
    CHECK(r.frames + r.skipped_ticks == 500);
    CHECK(r.misses <= r.frames);
    CHECK(r.elapsed_s >= 0.499);
    CHECK(calls == r.frames);
    CHECK(r.frame_ms.size() == r.frames);
  }
}

TEST_CASE("haptic loop: a scripted device pulls the part along its trajectory and holds it at the end") {
  Trajectory script;
  Keyframe a, b;
  a.time_s = 0;
  a.pose.translation = Vector3d(0, 0, 10);
  b.time_s = 0.5;
  b.pose.translation = Vector3d(2, 0, -5);
  b.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vector3d::UnitX()));
  script.keyframes = {a, b};
  ScriptedDevice device(script, DeviceLimits{5.0, 0.5});
  ManualClock clock;
  CostedEvaluator engine{&clock};
  BodyState part;
  part.pose = a.pose;
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), config(1.5), clock.clock(), part);
  CHECK((r.final_part.pose.translation - b.pose.translation).norm() < 1e-3);
  CHECK(rotation_between(r.final_part.pose.rotation, b.pose.rotation).norm() < 1e-3);
  // The device felt the coupling while the part lagged, never more than its limits.
  double peak = 0;
  for (const FrameRecord& f : r.log) {
    CHECK(f.sent.force.norm() <= 5.0 + 1e-12);
    CHECK(f.sent.torque.norm() <= 0.5 + 1e-12);
    peak = std::max(peak, f.sent.force.norm());
  }
  CHECK(peak > 0.1);
  CHECK(device.sent_count() == r.frames);
}

TEST_CASE("haptic loop: NaN device readings are replaced by the last good one and never reach the device") {
  struct GlitchyDevice : FixedDevice {
    std::size_t reads = 0;
    BodyState read(double t) override {
      BodyState s = FixedDevice::read(t);
      if (++reads % 7 == 0) s.pose.translation.x() = NAN;
      if (reads % 11 == 0) s.velocity.y() = INFINITY;
      if (reads % 13 == 0) s.pose.rotation.coeffs() *= 0;  // not a rotation
      return s;
    }
    Wrench last;
    void send(const Wrench& w, double) override {
      last = w, ++sent, all_finite = all_finite && w.force.allFinite() && w.torque.allFinite();
    }
    bool all_finite = true;
  } device;
  device.state.pose.translation = Vector3d(3, 0, 0);
  ManualClock clock;
  CostedEvaluator engine{&clock};
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), config(1.0), clock.clock(), BodyState{});
  CHECK(r.bad_device_reads > 100);
  CHECK(r.part_resets == 0);
  CHECK(device.all_finite);
  CHECK((r.final_part.pose.translation - Vector3d(3, 0, 0)).norm() < 1e-3);
}

TEST_CASE("haptic loop: misses from waking late are counted but do not step m' down") {
  ManualClock clock;
  FixedDevice device;
  CostedEvaluator engine{&clock};
  LoopClock late = clock.clock();
  std::size_t waits = 0;
  // The OS wakes the loop 1.2 ms late at waits 300 and 320: two misses in 100 frames.
  late.wait_until = [&clock, &waits](double until) {
    ++waits;
    clock.t = std::max(clock.t, until) + ((waits == 300 || waits == 320) ? 1.2e-3 : 0.0);
  };
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), config(1.0), late, BodyState{});
  CHECK(r.misses == 2);
  CHECK(r.late_wakeup_misses == 2);
  CHECK(r.mode_changes.empty());
  REQUIRE(r.wake_late_ms.size() == r.frames);
  CHECK(*std::max_element(r.wake_late_ms.begin(), r.wake_late_ms.end()) == doctest::Approx(1.2));
}

TEST_CASE("haptic loop: misses from the loop's own callbacks running past the tick step m' down") {
  ManualClock clock;
  FixedDevice device;
  CostedEvaluator engine{&clock};
  LoopConfig c = config(1.0);
  c.modes.predicted_ms = [](std::size_t m) { return 0.02 * double(m) / 1000.0; };
  // Frames 200-209 spend 1.5 ms in on_frame, after their wrench is sent: the next tick
  // starts late without the thread ever sleeping, which is the loop's work, not the OS.
  std::size_t seen = 0;
  c.on_frame = [&](const FrameRecord&, const LoopReport&) {
    if (seen >= 200 && seen < 210) clock.t += 1.5e-3;
    ++seen;
  };
  const LoopReport r = run_haptic_loop(device, engine.evaluator(), c, clock.clock(), BodyState{});
  CHECK(r.misses >= 2);
  CHECK(r.late_wakeup_misses == 0);
  CHECK(r.stall_misses == 0);  // the query itself took what the model predicts
  REQUIRE(!r.mode_changes.empty());
  CHECK(r.mode_changes[0].to == 8192);
  CHECK(r.mode_changes[0].frame > 200);
  CHECK(r.mode_changes[0].frame < 212);
  // The OS never woke the loop late.
  CHECK(*std::max_element(r.wake_late_ms.begin(), r.wake_late_ms.end()) == 0.0);
}

TEST_CASE("haptic loop: stalls far beyond the cost model are counted but do not step m' down, unless they persist") {
  // Model: 0.02 ms per 1000 modes, as the evaluator costs (0.33 ms at 16384); `extra`
  // adds ms of work at given queries.
  auto run = [](const std::map<std::size_t, double>& extra) {
    ManualClock clock;
    FixedDevice device;
    CostedEvaluator engine{&clock};
    engine.extra = extra;
    LoopConfig c = config(1.0);
    c.modes.predicted_ms = [](std::size_t m) { return 0.02 * double(m) / 1000.0; };
    return run_haptic_loop(device, engine.evaluator(), c, clock.clock(), BodyState{});
  };
  {
    // Two 3 ms stalls within 100 frames: work ~10x the model's 0.33 ms.
    const LoopReport r = run({{200, 3.0}, {240, 3.0}});
    CHECK(r.misses == 2);
    CHECK(r.stall_misses == 2);
    CHECK(r.mode_changes.empty());
  }
  {
    // The same two misses with 0.9 ms of extra work (1.23 ms, 3.75x the model): work-bound.
    const LoopReport r = run({{200, 0.9}, {240, 0.9}});
    CHECK(r.misses == 2);
    CHECK(r.stall_misses == 0);
    REQUIRE(!r.mode_changes.empty());
    CHECK(r.mode_changes[0].to == 8192);
    CHECK(r.mode_changes[0].frame == 240);
  }
  {
    // A machine 8x slower than tuned from frame 100 on: every frame "stalls"; once they
    // fill half the window they count as misses and m' steps down.
    std::map<std::size_t, double> slow;
    for (std::size_t q = 100; q < 400; ++q) slow[q] = 2.4;
    const LoopReport r = run(slow);
    CHECK(r.stall_misses > 0);
    REQUIRE(!r.mode_changes.empty());
    CHECK(r.mode_changes[0].to == 8192);
  }
}
