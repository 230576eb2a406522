// snapfit/live.h: the main job's preparation, then the haptic loop on its own thread in
// segments of a few seconds (each reserves its frames' storage before it starts, so no
// frame allocates), until stopped. A reset or the start or end of a recording ends the
// current segment at its next frame and the next one starts at once.
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <thread>

#include "jobs/job_steps.h"
#include "jobs/live_device.h"
#include "scheduler/assembly_verdict.h"
#include "scheduler/haptic_setup.h"
#include "scheduler/rigid_contact.h"
#include "scheduler/thread_priority.h"
#include "snapfit/error.h"
#include "snapfit/live.h"

namespace snapfit {
namespace {

constexpr double kSegmentS = 10;  // loop time per segment
constexpr int kWarmupQueries = 50;
// A status measures part 2's surface deviation at most this often, and no more than a
// tenth of the time (a measure takes milliseconds; a page asks 60 times a second).
constexpr double kSurfacePeriodS = 0.1;

bool same_pose(const Pose& a, const Pose& b) {
  return a.translation == b.translation && a.rotation.coeffs() == b.rotation.coeffs();
}

// Appends a segment's report to the recording's.
void append_segment(LoopReport& all, const LoopReport& segment) {
  all.rate_hz = segment.rate_hz;
  all.elapsed_s += segment.elapsed_s;
  all.ticks += segment.ticks;
  all.frames += segment.frames;
  all.misses += segment.misses;
  all.skipped_ticks += segment.skipped_ticks;
  all.flagged_frames += segment.flagged_frames;
  all.trust_scaled_frames += segment.trust_scaled_frames;
  all.trust_withheld_frames += segment.trust_withheld_frames;
  all.out_of_region_frames += segment.out_of_region_frames;
  all.bad_device_reads += segment.bad_device_reads;
  all.part_resets += segment.part_resets;
  all.passivity_frames += segment.passivity_frames;
  all.passivity_dissipated_j += segment.passivity_dissipated_j;
  all.rate_limited_frames += segment.rate_limited_frames;
  all.rate_limit_dissipated_j += segment.rate_limit_dissipated_j;
  all.rate_slewed_frames += segment.rate_slewed_frames;
  all.rate_slew_work_j += segment.rate_slew_work_j;
  all.late_wakeup_misses += segment.late_wakeup_misses;
  all.stall_misses += segment.stall_misses;
  const double offset = all.log.empty() ? 0 : all.log.back().time_s + 1 / segment.rate_hz;
  all.frame_ms.insert(all.frame_ms.end(), segment.frame_ms.begin(), segment.frame_ms.end());
  all.wake_late_ms.insert(all.wake_late_ms.end(), segment.wake_late_ms.begin(), segment.wake_late_ms.end());
  for (FrameRecord f : segment.log) {
    f.time_s += offset;
    all.log.push_back(f);
  }
  for (ModeChange c : segment.mode_changes) {
    c.time_s += offset;
    all.mode_changes.push_back(c);
  }
  all.final_part = segment.final_part;
  all.final_modes = segment.final_modes;
  all.measured_rate_hz = all.elapsed_s > 0 ? all.frames / all.elapsed_s : 0;
}

}  // namespace

struct LiveSession::State {
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

  std::thread thread;
  std::atomic<bool> quit{false}, segment_stop{false}, reset_requested{false};
  std::exception_ptr error;

  // Published by the loop's thread (try_lock: a reader never makes a frame wait).
  mutable std::mutex frame_mutex;
  LiveFrame latest_frame;
  std::uint64_t frames_before_segment = 0;  // frames published so far (the loop's thread only)
  std::atomic<std::uint64_t> misses{0};     // frames that ended after their deadline
  double time_before_segment = 0;

  // Between the loop's thread and the callers: totals, the recording and its requests.
  mutable std::mutex mutex;
  std::condition_variable changed;
  LiveStatus status;
  bool record_wanted = false, recording = false;
  LoopReport recorded;
  std::uint64_t segments_done = 0;
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

  void publish(const FrameRecord& f);
  LiveFrame latest() const;
  // `fresh`: measure part 2's surface now if the pose moved, not at most every kSurfacePeriodS.
  LiveStatus make_status(bool fresh) const;
  double surface_deviation(const Pose& pose, bool fresh) const;
  void run();
  void after_segment(const LoopReport& segment, BodyState& part);
};

void LiveSession::State::publish(const FrameRecord& f) {
  const LiveDevice::Seen& seen = device->seen();
  LiveFrame frame;
  frame.frame = ++frames_before_segment;
  frame.time_s = time_before_segment + f.time_s;
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
  if (f.missed) ++misses;
  if (frame_mutex.try_lock()) {
    latest_frame = frame;
    frame_mutex.unlock();
  }
  if (options.on_frame) options.on_frame(frame);
}

void LiveSession::State::after_segment(const LoopReport& segment, BodyState& part) {
  time_before_segment += segment.elapsed_s;
  part = segment.final_part;
  if (reset_requested.exchange(false)) {
    part = initial;
    device->reset(initial);
  }
  const std::lock_guard<std::mutex> lock(mutex);
  status.part = part.pose;
  if (recording) append_segment(recorded, segment);
  if (record_wanted && !recording) recorded = LoopReport{};
  recording = record_wanted;
  status.recording = recording;
  ++segments_done;
  changed.notify_all();
}

void LiveSession::State::run() {
  try {
    BodyState part = initial;
    for (int i = 0; i < kWarmupQueries; ++i) evaluator.evaluate(part.pose);
    while (!quit) {
      LoopConfig c = config;
      c.duration_s = kSegmentS;
      {
        const std::lock_guard<std::mutex> lock(mutex);
        c.keep_log = recording;
      }
      c.stop = &segment_stop;
      c.on_frame = [this](const FrameRecord& f) { publish(f); };
      const LoopReport segment = run_haptic_loop(*device, evaluator, c, steady_loop_clock(request.loop_wait), part);
      segment_stop = false;
      after_segment(segment, part);
    }
  } catch (...) {
    error = std::current_exception();
    const std::lock_guard<std::mutex> lock(mutex);
    ++segments_done;
    changed.notify_all();
  }
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
  s.prepared = job_result(s.job.record);
  s.latest_frame.part = s.latest_frame.device = s.initial.pose;
  s.status.part = s.initial.pose;
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
  s.priority = raise_process_priority(loop_priority(PriorityRequest{-20, 10}, s.request.loop_wait));
  s.session.priority = s.priority;
  s.thread = std::thread([&s] { s.run(); });
}

LiveStatus LiveSession::stop() {
  State& s = *state_;
  if (s.thread.joinable()) {
    s.quit = true;
    s.segment_stop = true;
    s.thread.join();
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

void LiveSession::reset() {
  state_->reset_requested = true;
  state_->segment_stop = true;
}

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
  {
    const std::lock_guard<std::mutex> lock(mutex);
    out = status;
  }
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
  {
    const std::lock_guard<std::mutex> lock(s.mutex);
    s.record_wanted = true;
  }
  s.segment_stop = true;
}

JobResult LiveSession::stop_recording() {
  State& s = *state_;
  std::unique_lock<std::mutex> lock(s.mutex);
  if (!s.record_wanted && !s.recording) throw Error("live session: no recording to stop");
  s.record_wanted = false;
  if (s.thread.joinable()) {
    // Wait for the segment that ends the recording (it ends at its next frame).
    const std::uint64_t after = s.segments_done;
    s.segment_stop = true;
    s.changed.wait(lock, [&] { return s.segments_done > after && !s.recording; });
  }
  if (s.error) std::rethrow_exception(s.error);
  auto record = std::make_shared<JobRecord>(*s.job.record);
  SessionResult session = s.session;
  session.loop = std::move(s.recorded);
  s.recorded = LoopReport{};
  s.recording = false;
  lock.unlock();
  judge_session_end(session, s.scene, s.job.pair->part(2).mesh);
  record->session = std::move(session);
  return job_result(std::move(record));
}

}  // namespace snapfit
