// snapfit/live.h: the main job's preparation, then one haptic loop on its own thread
// until stopped (its m' governor, passivity controller and force slew carried over every
// frame). A reset replaces part 2's state between two frames; a recording is the frames
// between its start and its end, handed by the loop through a lock-free queue to a
// recorder thread, which does the allocating: no frame allocates.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <optional>
#include <thread>

#include "core/spsc_ring.h"
#include "jobs/job_steps.h"
#include "scheduler/haptics/live_device.h"
#include "scheduler/haptics/assembly_verdict.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/rigid_contact.h"
#include "scheduler/haptics/thread_priority.h"
#include "snapfit/error.h"
#include "snapfit/live.h"

namespace snapfit {
namespace {

constexpr int kWarmupQueries = 50;
// A status measures part 2's surface deviation at most this often, and no more than a
// tenth of the time (a measure takes milliseconds; a page asks 60 times a second).
constexpr double kSurfacePeriodS = 0.1;
// The recorder's queue: 8 s of frames at 1 kHz; it is drained every kRecorderPeriod.
constexpr std::size_t kRecorderQueue = 8192;
constexpr auto kRecorderPeriod = std::chrono::milliseconds(10);

bool same_pose(const Pose& a, const Pose& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}

}  // namespace

struct LiveSession::State {
  // What the loop hands the recorder: a frame (with the m' change it made, if any), or a
  // recording's start or end (with its counts). Plain data: copied without allocation.
  struct RecorderItem {
    enum Kind : std::uint8_t { frame, begin, end } kind = frame;
    FrameRecord record;
    bool mode_changed = false;
    std::size_t modes_from = 0, modes_to = 0;
    char reason[96] = {};
    LoopCounts counts;          // end: the recording's
    std::uint64_t dropped = 0;  // end: frames the full queue refused
  };

  State() : queue(kRecorderQueue) {}
  Scene scene;
  JobRequest request;
  LiveOptions options;
  JobResult prepared;
  PreparedJob job;
  LoopConfig config;
  SessionResult session;  // the loop's facts, for a recording's result
  std::optional<AssemblyJudge> judge;  // when the scene has an assembled pose
  BodyState initial;
  std::unique_ptr<LiveDevice> device;
  WrenchEvaluator evaluator;

  std::thread thread, recorder;
  std::atomic<bool> quit{false}, reset_requested{false}, loop_ended{false};
  std::exception_ptr error;

  // Published by the loop's thread (try_lock: a reader never makes a frame wait).
  mutable std::mutex frame_mutex;
  LiveFrame latest_frame;
  std::atomic<std::uint64_t> misses{0};  // frames that ended after their deadline

  // Recordings. Odd epochs record: start and stop each add one (under record_mutex, one
  // call at a time); the loop's thread follows the epoch between frames.
  std::mutex record_mutex;
  std::atomic<std::uint64_t> record_epoch{0};
  // The loop's thread only.
  std::uint64_t seen_epoch = 0;
  LoopCounts record_start;
  std::size_t mode_changes_seen = 0;
  double record_t0 = 0;
  std::uint64_t dropped = 0;
  SpscRing<RecorderItem> queue;
  RecorderItem item;  // the one being filled (not on the loop's stack: it is large)

  // The recorder's, handed to stop_recording under `mutex`.
  mutable std::mutex mutex;
  std::condition_variable changed;
  LoopReport building, finished;
  std::uint64_t finished_dropped = 0;  // frames of `finished` the full queue refused
  std::uint64_t recordings_finished = 0;
  bool recorder_done = false;  // its thread has drained the queue after the loop ended
  PriorityChange priority;

  // The status's last surface measure (surface_deviation()).
  struct SurfaceMeasure {
    bool made = false;
    Pose pose;
    double distance = 0;
    std::chrono::steady_clock::time_point at;
    double cost_s = 0;
  };
  mutable std::mutex surface_mutex;
  mutable SurfaceMeasure surface;

  void publish(const FrameRecord& f, const LoopReport& so_far);
  void follow_recording(const FrameRecord& f, const LoopReport& so_far);
  void hand_over(State::RecorderItem::Kind kind, const LoopReport& so_far);
  LiveFrame latest() const;
  // `fresh`: measure part 2's surface now if the pose moved, not at most every kSurfacePeriodS.
  LiveStatus make_status(bool fresh) const;
  double surface_deviation(const Pose& pose, bool fresh) const;
  bool replace_part(BodyState& part);
  void run();
  void record();
  void take(const RecorderItem& item);
};

void LiveSession::State::publish(const FrameRecord& f, const LoopReport& so_far) {
  const LiveDevice::Seen& seen = device->seen();
  LiveFrame frame;
  frame.frame = so_far.frames;
  frame.time_s = f.time_s;
  frame.sequence = seen.sequence;
  frame.device = f.device;
  frame.part = f.part;
  frame.energy = f.energy;
  frame.geometric = f.geometric;
  frame.trust = f.trust;
  frame.contact = f.contact;
  frame.contact_depth = f.contact_depth;
  frame.sent = seen.sent;
  frame.fade = seen.fade;
  frame.late = seen.late;
  frame.modes = f.modes;
  frame.frame_ms = f.frame_ms;
  frame.flags = f.flags;
  frame.missed = f.missed;
  misses = so_far.misses;
  if (frame_mutex.try_lock()) {
    latest_frame = frame;
    frame_mutex.unlock();
  }
  follow_recording(f, so_far);
  if (options.on_frame) options.on_frame(frame);
}

// Queues a recording's start or end (a marker is always queued: frames leave it room).
void LiveSession::State::hand_over(State::RecorderItem::Kind kind, const LoopReport& so_far) {
  item.kind = kind;
  item.mode_changed = false;
  if (kind == State::RecorderItem::begin) {
    record_start = so_far;
    mode_changes_seen = so_far.mode_changes.size();
    dropped = 0;
  } else {
    item.counts = counts_between(record_start, so_far);
    item.dropped = dropped;
  }
  queue.push(item);
}

// On the loop's thread after each frame: queues the frame while recording, then starts
// and ends recordings as the epoch says (a recording holds the frames from the one after
// its start was seen to the one in which its end was).
void LiveSession::State::follow_recording(const FrameRecord& f, const LoopReport& so_far) {
  if (seen_epoch % 2 == 1) {
    if (record_t0 < 0) record_t0 = f.time_s;  // the recording's time starts at its first frame
    item.kind = RecorderItem::frame;
    item.record = f;
    item.record.time_s -= record_t0;
    item.mode_changed = so_far.mode_changes.size() > mode_changes_seen;
    if (item.mode_changed) {
      const ModeChange& c = so_far.mode_changes.back();
      mode_changes_seen = so_far.mode_changes.size();
      item.modes_from = c.from, item.modes_to = c.to;
      std::strncpy(item.reason, c.reason.c_str(), sizeof item.reason - 1);
    }
    if (!queue.push(item, 2)) ++dropped;  // two slots kept for a recording's end and the next start
  }
  const std::uint64_t epoch = record_epoch.load(std::memory_order_acquire);
  if (epoch == seen_epoch) return;
  const bool was = seen_epoch % 2 == 1, wants = epoch % 2 == 1;
  if (was) hand_over(RecorderItem::end, so_far);
  if (!was && !wants) {  // started and stopped between two frames: an empty recording
    hand_over(RecorderItem::begin, so_far);
    hand_over(RecorderItem::end, so_far);
  }
  if (wants) {
    hand_over(RecorderItem::begin, so_far);  // from the next frame on: this one's counts are before it
    record_t0 = -1;
  }
  seen_epoch = epoch;
}

// A reset asked for from another thread: part 2 and the device back to the start, between frames.
bool LiveSession::State::replace_part(BodyState& part) {
  if (!reset_requested.exchange(false)) return false;
  part = initial;
  device->reset(initial);
  return true;
}

void LiveSession::State::run() {
  try {
    BodyState part = initial;
    for (int i = 0; i < kWarmupQueries; ++i) evaluator.evaluate(part.pose);
    LoopConfig c = config;
    c.duration_s = 0;  // until stopped
    c.stop = &quit;
    c.keep_log = false;
    c.keep_frame_times = false;
    c.on_frame = [this](const FrameRecord& f, const LoopReport& so_far) { publish(f, so_far); };
    c.replace_part = [this](BodyState& p) { return replace_part(p); };
    const LoopReport last = run_haptic_loop(*device, evaluator, c, steady_loop_clock(request.loop_wait), part);
    if (seen_epoch % 2 == 1) hand_over(State::RecorderItem::end, last);  // stopped while recording
  } catch (...) {
    error = std::current_exception();
  }
  loop_ended = true;
}

// The recorder's side of one item.
void LiveSession::State::take(const RecorderItem& it) {
  if (it.kind == State::RecorderItem::begin) {
    building = LoopReport{};
    return;
  }
  if (it.kind == State::RecorderItem::frame) {
    building.log.push_back(it.record);
    building.frame_ms.push_back(it.record.frame_ms);
    building.wake_late_ms.push_back(it.record.wake_late_ms);
    if (it.mode_changed)
      building.mode_changes.push_back(ModeChange{it.record.time_s, building.log.size() - 1, it.modes_from,
                                                 it.modes_to, std::string(it.reason)});
    return;
  }
  static_cast<LoopCounts&>(building) = it.counts;
  const std::lock_guard<std::mutex> lock(mutex);
  finished = std::move(building);
  finished_dropped = it.dropped;
  building = LoopReport{};
  ++recordings_finished;
  changed.notify_all();
}

// The recorder's thread: drains the loop's queue until the loop has ended and the queue is empty.
void LiveSession::State::record() {
  RecorderItem it;
  for (;;) {
    const bool ended = loop_ended.load();
    while (queue.pop(it)) take(it);
    if (ended) break;
    std::this_thread::sleep_for(kRecorderPeriod);
  }
  const std::lock_guard<std::mutex> lock(mutex);
  recorder_done = true;
  changed.notify_all();
}

namespace {

// A person moves the device anywhere, not along the scene's trajectory: only a declared
// workspace bounds part 1's region (pipeline/reach_region.h).
Scene live_scene(const Scene& scene) {
  Scene live = scene;
  if (live.grid.region.kind == RegionKind::reach) live.grid.region.kind = RegionKind::whole;
  return live;
}

}  // namespace

LiveSession::LiveSession(const Scene& scene_in, const JobRequest& request, const LiveOptions& options)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  const Scene scene = live_scene(scene_in);
  if (uses_vps(scene.method))
    throw Error("a live session renders the snapfit method; scene method '" + std::string(method_name(scene.method)) +
                "' runs with `snapfit run`");
  if (request.simulated_time) throw Error("a live session runs on the steady clock, not simulated time");
  if (!(options.late_s > 0) || !(options.fade_s >= 0))
    throw Error("live session: late_s must be > 0 and fade_s >= 0");
  s.scene = scene;
  s.request = request;
  s.options = options;
  const JobOutput out = job_output(request);
  s.job = prepare_job(scene, request, out, prepare_job_parts(scene, request, out));
  const AssemblyPair& pair = *s.job.pair;
  const std::string contact_off = s.job.record->contact_off;
  std::shared_ptr<const RigidContactModel> contact = s.job.record->contact;
  if (!contact_off.empty()) out.note(contact_off);
  double force_scale = 0;
  std::optional<double> contact_ms;
  if (s.job.record->contact_reserved_ms > 0) contact_ms = s.job.record->contact_reserved_ms;
  s.config = loop_config_for(scene, pair.part(2).mesh, pair.spectra.spacing, *s.job.loop_engine, s.job.record->tuning,
                             force_scale, contact, contact_ms);
  s.config.in_region = region_guard(pair.region);
  s.session = session_before_loop(scene, pair.spectra.spacing, s.config);
  if (scene.assembled_pose)
    s.judge.emplace(pair.part(2).mesh, *scene.assembled_pose, s.session.position_tolerance,
                    s.session.angle_tolerance_deg);
  s.session.force_scale = force_scale;
  s.session.contact = contact;
  s.session.contact_off = contact_off;
  s.session.wait = request.loop_wait;
  s.initial.pose = scene.part2.pose;
  s.device = std::make_unique<LiveDevice>(s.initial, s.session.limits, options.late_s, options.fade_s);
  s.evaluator = wrench_evaluator(*s.job.loop_engine);
  s.prepared = job_result(*s.job.record);
  s.latest_frame.part = s.latest_frame.device = s.initial.pose;
}

LiveSession::~LiveSession() {
  try {
    stop();
  } catch (...) {  // a destructor does not throw; stop() is where the error is seen
  }
}

const JobResult& LiveSession::prepared() const { return state_->prepared; }

void LiveSession::start() {
  State& s = *state_;
  if (s.thread.joinable()) throw Error("live session: already started");
  s.quit = false;
  s.loop_ended = false;
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.recorder_done = false;
  }
  s.priority = raise_process_priority(loop_priority(PriorityRequest{-20, 10}, s.request.loop_wait));
  s.session.priority = s.priority;
  s.recorder = std::thread([&s] { s.record(); });
  s.thread = std::thread([&s] { s.run(); });
}

LiveStatus LiveSession::stop() {
  State& s = *state_;
  if (s.thread.joinable()) {
    s.quit = true;
    s.thread.join();
    s.recorder.join();  // after the loop's last item
    restore_process_priority(s.priority);
  }
  if (s.error) std::rethrow_exception(std::exchange(s.error, nullptr));
  return s.make_status(true);
}

void LiveSession::set_device_state(const BodyState& state, std::uint32_t sequence) {
  state_->device->set_state(state, sequence);
}

void LiveSession::hold_device_pose(const Pose& pose) {
  BodyState state;
  state.pose = pose;
  state_->device->set_state(state, 0, LiveDevice::Clock::now(), false);
}

void LiveSession::reset() { state_->reset_requested = true; }

LiveFrame LiveSession::State::latest() const {
  const std::lock_guard<std::mutex> lock(frame_mutex);
  return latest_frame;
}

LiveFrame LiveSession::latest() const { return state_->latest(); }

double LiveSession::State::surface_deviation(const Pose& pose, bool fresh) const {
  const std::lock_guard<std::mutex> lock(surface_mutex);
  const auto now = std::chrono::steady_clock::now();
  const double age = std::chrono::duration<double>(now - surface.at).count();
  const bool due = !surface.made || fresh || age >= std::max(kSurfacePeriodS, 10 * surface.cost_s);
  if (due && !(surface.made && same_pose(pose, surface.pose))) {
    surface.distance = judge->surface(pose).distance;
    surface.made = true;
    surface.pose = pose;
    surface.at = now;
    surface.cost_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - now).count();
  }
  return surface.distance;
}

LiveStatus LiveSession::State::make_status(bool fresh) const {
  LiveStatus out;
  out.recording = record_epoch.load() % 2 == 1;
  out.part = initial.pose;
  const LiveFrame frame = latest();
  out.frames = frame.frame;
  out.elapsed_s = frame.time_s;
  out.misses = misses;
  out.sanitised = device->sanitised_count();
  if (frame.frame > 0) out.part = frame.part;
  if (judge) {
    const PoseError e = pose_error(out.part, *scene.assembled_pose);
    out.evaluated = true;
    out.position_error = e.position;
    out.angle_error_deg = e.angle_deg;
    out.surface_deviation = surface_deviation(out.part, fresh);
    out.assembled = judge->assembled(e, out.surface_deviation);
  }
  return out;
}

LiveStatus LiveSession::status() const { return state_->make_status(false); }

void LiveSession::start_recording() {
  State& s = *state_;
  const std::lock_guard<std::mutex> serial(s.record_mutex);
  const std::uint64_t epoch = s.record_epoch.load();
  if (epoch % 2 == 0) s.record_epoch.store(epoch + 1, std::memory_order_release);
}

JobResult LiveSession::stop_recording() {
  State& s = *state_;
  const std::lock_guard<std::mutex> serial(s.record_mutex);
  const std::uint64_t epoch = s.record_epoch.load();
  if (epoch % 2 == 0) throw Error("live session: no recording to stop");
  std::unique_lock<std::mutex> lock(s.mutex);
  const std::uint64_t before = s.recordings_finished;
  s.record_epoch.store(epoch + 1, std::memory_order_release);
  if (s.thread.joinable()) {
    // The loop ends the recording after its next frame; the recorder then hands it over.
    // A loop that has ended (an error) ended it already.
    s.changed.wait(lock, [&] { return s.recordings_finished > before || s.recorder_done; });
  } else if (!s.recorder_done) {
    s.finished = LoopReport{};  // never started: nothing was recorded
  }
  if (s.error) std::rethrow_exception(s.error);
  JobRecord record = *s.job.record;
  SessionResult session = s.session;
  session.loop = std::move(s.finished);
  s.finished = LoopReport{};
  const std::uint64_t dropped = std::exchange(s.finished_dropped, 0);
  lock.unlock();
  if (dropped > 0)
    job_output(s.request).note("live session: " + std::to_string(dropped) +
                               " frames of the recording were not kept (the recorder fell behind)");
  judge_session_end(session, s.scene, s.job.pair->part(2).mesh);
  record.session = std::move(session);
  return job_result(std::move(record));
}

}  // namespace snapfit
