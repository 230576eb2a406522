#pragma once
// A live session: the main job's preparation (job.h: parts, device, fields, spectra,
// the strategy and m' for the frame budget), then the haptic loop at the scene's rate on
// its own thread until stopped (the virtual coupling, the passivity controller, the
// rigid contact), driven by whatever sets the device's state from another thread: a
// person's mouse in `snapfit serve`'s page, or a device program through the bridge
// (bridge.h). A state older than LiveOptions::late_s is held at rest and the wrench sent
// back fades to zero; the loop never sends a non-finite wrench.
//
//   snapfit::LiveSession session(snapfit::load_scene("scenes/default.json"));
//   session.start();
//   session.set_device_state(state);            // from the device's thread, every frame
//   snapfit::LiveFrame f = session.latest();    // what the loop did last
//   snapfit::LiveStatus s = session.stop();     // frames, misses, the final pose's verdict
#include <cstdint>
#include <functional>
#include <memory>

#include "snapfit/haptic_device.h"
#include "snapfit/job.h"

namespace snapfit {

struct LiveFrame {
  std::uint64_t frame = 0;    // frames since the session started
  double time_s = 0;          // loop time since the session started
  std::uint32_t sequence = 0; // of the device state the frame read
  Pose device;                // the device's pose the frame read
  Pose part;                  // part 2's pose the engine was queried at
  double energy = 0;
  Wrench geometric;           // the engine's wrench with the loop's gain, N and N m, as rendered (times trust)
  double trust = 1;           // the share of the engine's wrench its error estimate vouched for
  Wrench contact;             // the rigid contact's
  double contact_depth = 0;   // scene units
  Wrench sent;                // to the device, after the limits and the fade
  float fade = 1;             // 1: the device's state is fresh; 0: faded out
  bool late = false;
  std::size_t modes = 0;      // m'
  double frame_ms = 0;        // tick to wrench sent
  std::uint32_t flags = 0;    // the query's flags
  bool missed = false;
};

struct LiveOptions {
  double late_s = 0.005;  // a state older than this is late: held at rest, the wrench fading
  double fade_s = 0.1;    // the wrench fades from full to zero over this long after `late_s`
  // Called on the loop's thread after every frame (a device bridge sends the wrench from
  // it): keep it short, it runs inside the frame. Set before start().
  std::function<void(const LiveFrame&)> on_frame;
};

struct LiveStatus {
  std::uint64_t frames = 0, misses = 0;
  std::uint64_t sanitised = 0;  // wrenches that were not finite, sent as zero
  double elapsed_s = 0;
  bool recording = false;
  Pose part;                    // part 2 now
  // Part 2 against the scene's assembled pose (when it has one), with `snapfit run`'s
  // rule: assembled when the pose is within the position and angle tolerances, or part
  // 2's surface is within the position tolerance of where the assembled pose puts it
  // (a round peg turned about its axis is assembled).
  bool evaluated = false, assembled = false;
  double position_error = 0, angle_error_deg = 0;
  // The two-sided Hausdorff distance between part 2's surface now and at the assembled
  // pose, scene units. It takes milliseconds, so status() measures it at most every
  // 0.1 s, or ten times the measure's own time when that is longer (the last measure
  // stands until then); stop() measures it at the final pose.
  double surface_deviation = 0;
};

class LiveSession {
 public:
  // Prepares everything (JobRequest as run_job: device, modes, strategy, margin,
  // loop_wait, say, note; simulated_time is refused). Throws snapfit::Error naming what
  // failed; a "vps" or "vps_hybrid" scene is refused (the live loop renders the
  // snapfit method).
  explicit LiveSession(const Scene& scene, const JobRequest& request = {}, const LiveOptions& options = {});
  ~LiveSession();  // stops
  LiveSession(const LiveSession&) = delete;
  LiveSession& operator=(const LiveSession&) = delete;

  // What the preparation found: device, strategy, m' (no loop yet), and the record with
  // both parts for a display.
  const JobResult& prepared() const;

  void start();        // the loop's thread; part 2 starts at the scene's initial pose
  LiveStatus stop();   // ends the loop; rethrows an error of the loop's thread

  // Any thread: the device's state now (part 1's frame, scene units), and the sender's
  // sequence number, echoed in the frames that read it. A device program streams one a
  // frame: when the next is late the pose is held and the wrench fades.
  void set_device_state(const BodyState& state, std::uint32_t sequence = 0);
  // Any thread: a pose that holds until the next one (a mouse), never late.
  void hold_device_pose(const Pose& pose);
  // Any thread: part 2 and the device back to the scene's initial pose, at rest.
  void reset();
  LiveFrame latest() const;
  LiveStatus status() const;

  // Any thread: the frames from now on are kept; stop_recording() returns them as a
  // job result (its record writes a report folder as `snapfit run`'s does).
  void start_recording();
  JobResult stop_recording();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace snapfit
