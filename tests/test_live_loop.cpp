// A live session is one haptic loop from start() to stop() (jobs/live_session.cpp): 30 s
// on the shipped default scene with the tuned m' ladder, a device moving part 2 down into
// the hole, two recordings and a reset. Bursts of slow frames (on_frame spinning) make the
// m' governor step down shortly before each boundary; across every boundary the frames
// go on as one loop: numbered without a gap, the governor's lower m' kept (a new loop
// would start again at the ladder's top), no larger step of the force sent than the
// loop makes elsewhere, and each recording exactly the frames between its start and end.
#include <atomic>
#include <chrono>
#include <cmath>
#include <doctest/doctest.h>
#include <thread>
#include <vector>

#include "snapfit/live.h"
#include "snapfit/scene.h"

using namespace snapfit;
using LiveClock = std::chrono::steady_clock;

namespace {

constexpr double kBurstS = 0.1;       // slow frames for this long before a boundary
constexpr double kBurstLeadS = 0.5;   // the boundary this long after the burst starts
constexpr double kSlowFrameMs = 1.5;  // each slow frame's extra work

bool same_part_pose(const Pose& a, const Pose& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}

// The frame index in `frames` whose part pose and energy are those of `r`, from `from`.
std::size_t find_frame(const std::vector<LiveFrame>& frames, const FrameRecord& r, std::size_t from) {
  for (std::size_t i = from; i < frames.size(); ++i)
    if (same_part_pose(frames[i].part, r.part) && frames[i].energy == r.energy) return i;
  return frames.size();
}

}  // namespace

TEST_CASE("live session: one loop for 30 s, its m', passivity and slew carried over recordings and a reset") {
  Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  REQUIRE(scene.assembled_pose);
  // Without the rigid contact: its time, taken from the frame's budget, can leave a slow
  // machine's ladder one level long, and this test needs the governor to step down.
  scene.haptics.contact = false;

  std::vector<LiveFrame> frames;
  frames.reserve(40000);
  std::atomic<double> burst_from{-1};  // loop time of the current burst's start (< 0: none)
  LiveOptions options;
  options.on_frame = [&](const LiveFrame& f) {
    const double b = burst_from.load();
    if (b >= 0 && f.time_s >= b && f.time_s < b + kBurstS) {
      const auto until = LiveClock::now() + std::chrono::microseconds(int(1e3 * kSlowFrameMs));
      while (LiveClock::now() < until) {
      }
    }
    if (frames.size() < frames.capacity()) frames.push_back(f);
  };
  JobRequest request;
  request.strategy = "tricubic";
  LiveSession session(scene, request, options);

  // The device: from the start pose down to the assembled pose over 20 s, then held.
  std::atomic<bool> device_done{false};
  const Pose from = scene.part2.pose, to = *scene.assembled_pose;
  session.start();
  const LiveClock::time_point t0 = LiveClock::now();
  const auto seconds = [&] { return std::chrono::duration<double>(LiveClock::now() - t0).count(); };
  std::thread device([&] {
    std::uint32_t sequence = 0;
    for (auto next = t0; !device_done; next += std::chrono::milliseconds(1)) {
      std::this_thread::sleep_until(next);
      const double u = std::min(1.0, seconds() / 20);
      BodyState state;
      state.pose.translation = (1 - u) * from.translation + u * to.translation;
      state.pose.rotation = from.rotation.slerp(u, to.rotation);
      session.set_device_state(state, ++sequence);
    }
  });
  // A burst, then the boundary `act` kBurstLeadS later.
  const auto at = [&](double t, const auto& act) {
    while (seconds() < t - kBurstLeadS) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    burst_from = session.latest().time_s;
    while (seconds() < t) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    act();
  };
  std::vector<JobResult> recordings;
  at(3.0, [&] { session.start_recording(); });
  at(7.0, [&] { recordings.push_back(session.stop_recording()); });
  at(11.0, [&] { session.start_recording(); });
  at(15.0, [&] { recordings.push_back(session.stop_recording()); });
  double reset_after = 0;
  at(19.0, [&] {
    reset_after = session.latest().time_s;
    session.reset();
  });
  while (seconds() < 30) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  const LiveStatus end = session.stop();
  device_done = true;
  device.join();
  MESSAGE("30 s live: " << end.frames << " frames, " << end.misses << " misses, " << frames.size() << " seen");

  // One loop: every frame numbered in turn, its loop time increasing.
  REQUIRE(frames.size() > 20000);
  for (std::size_t i = 1; i < frames.size(); ++i) {
    REQUIRE(frames[i].frame == frames[i - 1].frame + 1);
    REQUIRE(frames[i].time_s > frames[i - 1].time_s);
  }
  CHECK(end.frames == frames.back().frame);

  // Each recording: exactly the frames of one run of the stream, in order.
  REQUIRE(recordings.size() == 2);
  std::vector<std::size_t> boundaries;  // first frame of a recording, first frame after it
  std::size_t searched = 0;
  for (const JobResult& r : recordings) {
    REQUIRE(r.loop);
    const LoopReport& loop = *r.loop;
    REQUIRE(loop.log.size() > 3000);
    CHECK(loop.frames == loop.log.size());
    CHECK(loop.frame_ms.size() == loop.log.size());
    CHECK(loop.log.front().time_s == 0);
    const std::size_t first = find_frame(frames, loop.log.front(), searched);
    REQUIRE(first + loop.log.size() <= frames.size());
    std::size_t missed = 0;
    for (std::size_t i = 0; i < loop.log.size(); ++i) {
      REQUIRE(same_part_pose(frames[first + i].part, loop.log[i].part));
      REQUIRE(frames[first + i].energy == loop.log[i].energy);
      missed += loop.log[i].missed;
    }
    CHECK(loop.misses == missed);
    CHECK(loop.final_modes == loop.log.back().modes);
    boundaries.push_back(first);
    boundaries.push_back(first + loop.log.size());  // the first frame after it
    searched = first + loop.log.size();
  }
  std::size_t reset_frame = 0;  // the first frame at the initial pose after the reset
  for (std::size_t i = 1; i < frames.size() && !reset_frame; ++i)
    if (frames[i].time_s > reset_after && same_part_pose(frames[i].part, scene.part2.pose)) reset_frame = i;
  REQUIRE(reset_frame > 0);
  boundaries.push_back(reset_frame);

  // The governor stepped down in each burst and kept its m' over the boundary after it.
  const std::size_t top = frames.front().modes;  // the governor starts at the ladder's top
  REQUIRE(session.prepared().tuning.points.front().modes < top);  // a ladder it can step down
  for (std::size_t b : boundaries) {
    CAPTURE(b);
    CAPTURE(frames[b].time_s);
    CHECK(frames[b - 1].modes < top);  // the burst before it took m' down
    CHECK(frames[b].modes == frames[b - 1].modes);
  }

  // The force sent: no larger step at a recording's boundary than in the loop's other
  // quiet frames (no burst, no miss, not beside the reset, which moves part 2).
  const auto step = [&](std::size_t i) { return (frames[i].sent.force - frames[i - 1].sent.force).norm(); };
  const auto in_burst = [&](double t) {  // a burst and the frames that catch up after it
    for (std::size_t b : boundaries)
      if (t > frames[b].time_s - kBurstLeadS - 0.01 && t < frames[b].time_s - kBurstLeadS + kBurstS + 0.05) return true;
    return false;
  };
  const auto quiet = [&](std::size_t i) {
    for (std::size_t j = i - 1; j <= std::min(i + 1, frames.size() - 1); ++j)
      if (frames[j].missed) return false;
    const double t = frames[i].time_s;
    return !in_burst(t) && !(t > reset_after - 0.01 && t < reset_after + 0.2);
  };
  std::size_t outside_bursts = 0;  // misses the bursts did not cause: a busy machine
  for (const LiveFrame& f : frames) outside_bursts += f.missed && !in_burst(f.time_s);
  MESSAGE(outside_bursts << " misses outside the bursts");
  double elsewhere = 0, at_boundaries = 0;
  std::size_t counted = 0;
  for (std::size_t i = 2; i < frames.size(); ++i) {
    if (!quiet(i)) continue;
    bool near = false;
    for (std::size_t k = 0; k + 1 < boundaries.size(); ++k) near = near || (i >= boundaries[k] && i <= boundaries[k] + 1);
    if (near)
      at_boundaries = std::max(at_boundaries, step(i));
    else
      elsewhere = std::max(elsewhere, step(i)), ++counted;
  }
  MESSAGE("largest step of the sent force: " << at_boundaries << " N at the recordings' boundaries, " << elsewhere
                                             << " N over " << counted << " other quiet frames");
  CHECK(counted > 10000);
  CHECK(at_boundaries <= elsewhere);
  CHECK(elsewhere > 0);  // the force did change: the device moved part 2 into contact
}
