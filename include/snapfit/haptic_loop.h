#pragma once
// The fixed-rate haptic loop (1 kHz by default) on absolute deadlines. Each frame, at
// tick i (time i / rate):
//   1. read the device pose and velocity;
//   2. ask the engine for the geometric energy, force and torque at the part's pose;
//   3. integrate the part one step under the virtual coupling (implicit) and the
//      geometric wrench scaled by `geometry_gain` (explicit), with the passivity controller's damping (below);
//   4. send the coupling's reaction to the device, clamped to its limits.
// A frame that ends after its deadline (tick i + 1) is a miss: the device kept the last
// wrench meanwhile, and the ticks that passed are not replayed (no catch-up burst); the
// part is integrated over them with the held geometric wrench (the physics stays on
// the fixed step). A miss whose own work (wake-up to wrench sent, plus whatever of the
// previous frame's callbacks ran past this tick) fit in `up_headroom` of the budget is
// a late wake-up, which m' cannot fix; it is counted, not acted on.
// So is a stall: a miss whose work took more than `stall_factor` times the cost model's
// p99 at its m' (`predicted_ms`), which a smaller m' would not have avoided (the
// machine stopped), unless stalls fill more than half of the last `miss_window` frames, when the machine
// is simply slower than tuned and they count as work-bound misses.
// When work-bound misses repeat (`misses_to_step_down` within `miss_window` frames),
// m' steps down one level of the ladder at once; it steps up again, one level
// at a time up to the tuned m', only after `up_after_frames` frames without a miss
// (judged every `miss_window` frames) whose p99 frame time, scaled by the cost ratio of the next level, fits
// `up_headroom` of the budget. Every change is reported.
//
// Passivity: the geometric wrench is the gradient of the potential
// V = gain * E * metres_per_unit, but it is held over each step (explicit), which
// creates energy when the geometry is stiff against the step: dt^2 K_geometric above
// about 4 m + 2 dt b + dt^2 k makes the loop unstable. A passivity observer (Hannaford
// & Ryu 2002) compares, each frame, the work the held wrench did over the last step,
// F.dx + tau.dtheta, with the drop of V the engine reports at the new pose; the
// difference is energy the step created. The controller removes it in the next frames
// with extra damping of the part's velocity (implicit, mass-proportional:
// beta = alpha m, beta_R = alpha I, alpha dt <= 10), so the created energy not yet
// removed never exceeds one step's. Frames whose query is flagged, whose m' changed, or
// that follow a missed frame are not observed (V is not comparable there).
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "snapfit/haptic_device.h"
#include "snapfit/query.h"
#include "snapfit/tuning.h"

namespace snapfit {

class Assembly;

// The 6-DOF virtual coupling between the device and part 2 (Faas 2010 eq. 1-2):
// F = k_T d - b_T v, tau = k_R theta - b_R omega, d and theta from the part to the
// device. Units: poses in scene units, forces in N, torques in N m, masses in kg; the
// part is a proxy with isotropic inertia about its frame origin (part 2's reference
// point, where the engine's torque acts).
struct CouplingParams {
  double metres_per_unit = 1e-3;
  double mass_kg = 0.05;
  double inertia_kg_m2 = 1e-5;  // isotropic, about the part's reference point
  double stiffness = 800;       // k_T, N / m
  double rot_stiffness = 0.08;  // k_R, N m / rad
  double damping = 0;           // b_T, N s / m
  double rot_damping = 0;       // b_R, N m s / rad
};

// Time source of the loop (seconds); the steady clock in use, a manual one in tests.
struct LoopClock {
  std::function<double()> now;
  std::function<void(double)> wait_until;  // returns at or after the given time
};

// How a steady-clock loop waits for its next tick.
//   spin:  polls the clock through the whole wait, so its CPU never idles. On a virtual
//          machine an idle vCPU is halted, and the host can take a millisecond or more to
//          resume it for a timer (docs/haptics.md "Waiting for the tick"), longer than a
//          frame. Costs one core; run it at a nice value, not SCHED_FIFO (the kernel's
//          real-time throttling stops a SCHED_FIFO thread that never sleeps for 50 ms of
//          each second).
//   sleep: sleeps until ~0.2 ms before the deadline, then spins: frees the core between
//          frames, for machines whose timers wake a thread on time.
enum class LoopWait { spin, sleep };
const char* loop_wait_name(LoopWait wait);          // "spin" or "sleep"
LoopWait parse_loop_wait(const std::string& name);  // throws snapfit::Error for another name

// std::chrono::steady_clock, waiting as `wait` says.
LoopClock steady_loop_clock(LoopWait wait = LoopWait::spin);

// Simulated time: it moves only when the loop waits, so every frame takes no time and
// the run is deterministic (offline runs and tests of the physics; no timing meaning).
LoopClock simulated_loop_clock();

// The engine as the loop sees it: a query at a pose, and a way to change m'.
// `evaluate_state`, when set, is used instead of `evaluate`: for methods whose wrench
// depends on the part's velocity too (Voxmap PointShell's pre-contact braking).
struct WrenchEvaluator {
  std::function<QueryResult(const Pose&)> evaluate;
  std::function<void(std::size_t)> set_modes;
  std::function<QueryResult(const BodyState&)> evaluate_state;
};

// Rigid contact between the parts at a pose (docs/haptics.md "Rigid contact"): the wrench on
// part 2, the potential it derives from, and its stiffness, which the loop integrates
// implicitly so that a contact far stiffer than the coupling stays stable at 1 kHz.
struct ContactWrench {
  double energy_j = 0;  // the contact potential
  Wrench wrench;        // on part 2: N, and N m about its reference point
  // -d(force, torque) / d(translation in m, rotation in rad), symmetric positive
  // semi-definite (Gauss-Newton): blocks N/m, N/rad; N m/m, N m/rad.
  Eigen::Matrix<double, 6, 6> stiffness = Eigen::Matrix<double, 6, 6>::Zero();
  std::size_t points = 0;  // surface points in contact
  double depth = 0;        // the deepest point's interpenetration, scene units
};

struct FrameRecord {
  double time_s = 0;         // the frame's tick time
  double frame_ms = 0;       // tick to wrench sent
  Pose device;               // the device's pose read this frame
  Pose part;                 // the part's pose the engine was queried at (before this frame's step)
  double energy = 0;         // engine energy at `part`
  Wrench geometric;          // as rendered: the engine's scaled to N, N m, times `trust` (rigid contact is `contact`)
  Wrench contact;            // rigid contact (LoopConfig::contact), N, N m
  double contact_depth = 0;  // its deepest point's interpenetration, scene units
  // The engine's error estimate for `energy` and `geometric` (same units as they).
  ErrorEstimate geometric_error;
  Wrench sent;  // to the device, after clamping
  std::size_t modes = 0;
  std::uint32_t flags = 0;  // QueryFlags of the engine
  bool missed = false;
  std::uint8_t constraint = 0;   // QueryResult::constraint: the hybrid's engaged constraint
  double constraint_weight = 0;  // and its blend weight x
  double trust = 1;              // the share of the engine's wrench rendered (WrenchTrust); 0 when flagged
  double wake_late_ms = 0;       // how late the OS woke the loop's thread (after the tick, or after the
                                 // previous frame's callbacks when they ran past it)
};

// How much of the engine's wrench the loop renders, from its per-query error estimate
// (include/snapfit/query.h ErrorEstimate): all of it where the estimate is within the
// tolerance, the larger of `relative` times the value and the absolute floor (force_n,
// torque_nm after the gain); none where the estimate reaches the value itself (its
// direction is then not known); linearly in between, the whole wrench by the smaller of
// the force's and the torque's weights. A weight w < 1 shrinks the wrench towards zero: if
// the estimate covers the true error, the rendered force never pushes against the exact
// one and is never stronger than it (scheduler/haptics/wrench_trust.h).
struct WrenchTrust {
  bool enabled = true;
  double relative = 0.2;
  double force_n = 0.05;
  double torque_nm = 1e-3;
};

struct ModePolicy {
  std::vector<std::size_t> levels;                  // increasing m' values; the last one is the tuned m'
  std::function<double(std::size_t)> predicted_ms;  // cost model for step-up; null: proportional to m'
  std::size_t miss_window = 100;
  std::size_t misses_to_step_down = 2;
  std::size_t up_after_frames = 2000;
  double up_headroom = 0.6;
  double stall_factor = 4;  // work beyond this multiple of predicted_ms(m') is a stall (0: none)
};

struct LoopReport;

struct LoopConfig {
  double rate_hz = 1000;
  double duration_s = 1;  // loop time to run; <= 0 runs until `stop` is set
  double budget_ms = 1;   // the frame budget the policy measures headroom against
  CouplingParams coupling;
  double geometry_gain = 1;  // N per engine force unit (loop_config sets it from the scene)
  ModePolicy modes;
  bool passivity_control = true;  // observer + damping controller on the geometric wrench (above)
  WrenchTrust trust;              // the engine's wrench only as far as its error estimate vouches for it
  // Speed limit: the most the part's origin moves (scene units) and turns (rad) in one
  // step; 0 = none. Voxmap PointShell sets it (no point moves more than half a voxel).
  double max_travel = 0;
  double max_rotation = 0;
  bool keep_log = true;  // one FrameRecord per frame
  // LoopReport::frame_ms and wake_late_ms, one value per frame. Off for a loop that runs
  // until stopped (a live session): its storage would grow without end, and reallocate.
  bool keep_frame_times = true;
  // Called on the loop's thread at the end of each frame with its record and the report
  // so far (its counts include this frame and the ticks it overran; its vectors hold what
  // keep_log and keep_frame_times keep): a live display, a device bridge, a recorder.
  // Keep it short, it runs inside the frame's budget; null: none.
  std::function<void(const FrameRecord&, const LoopReport& so_far)> on_frame;
  // Called on the loop's thread at each tick before its frame: may set the part's state
  // anew (a reset) and then returns true. The loop forgets the last frame's pose (the
  // passivity observer's step and the force-rate bound's last force) but keeps its m'
  // governor, the passivity controller's energy budget and the force slew's tank, as it
  // does over any frame. null: never.
  std::function<bool(BodyState& part)> replace_part;
  const std::atomic<bool>* stop = nullptr;
  // Rigid contact at the part's pose, added to the geometric wrench each frame, its
  // stiffness integrated implicitly; null: none (Behandish & Ilies 2016's energy alone).
  std::function<ContactWrench(const Pose&)> contact;
  double contact_ms = 0;  // its measured time per frame (p99), left out of the query's share of the budget
  // False where part 2 leaves the region part 1's fields cover (the scene's grid.region):
  // there the engine's wrench is not rendered (counted in LoopReport::out_of_region_frames);
  // null: everywhere.
  std::function<bool(const Pose&)> in_region;
  // The most the coupling's force on the device may change per second (N/s; 0: no bound):
  // a frame that would change it faster damps the part instead (passive: the energy is
  // dissipated, not sent to the hand). See docs/haptics.md.
  double max_force_rate_n_per_s = 0;
};

struct ModeChange {
  double time_s = 0;
  std::size_t frame = 0;
  std::size_t from = 0, to = 0;
  std::string reason;
};

// What a loop has counted: plain data, copied without allocation (a live session
// takes the counts at a recording's start and end; the recording's are the difference).
struct LoopCounts {
  double rate_hz = 0;           // the configured rate
  double measured_rate_hz = 0;  // frames run / wall time of the loop
  double elapsed_s = 0;
  std::size_t ticks = 0;                // ticks that came due
  std::size_t frames = 0;               // frames run (ticks - skipped)
  std::size_t misses = 0;               // frames that ended after their deadline
  std::size_t skipped_ticks = 0;        // ticks not run because a frame overran them
  std::size_t flagged_frames = 0;       // frames whose query returned flags (zero geometric wrench)
  std::size_t trust_scaled_frames = 0;    // frames whose engine wrench was rendered in part (WrenchTrust)
  std::size_t trust_withheld_frames = 0;  // frames whose engine wrench was not rendered: its estimate vouched for none
  std::size_t out_of_region_frames = 0;   // frames with part 2 outside the region its fields cover (not rendered)
  std::size_t bad_device_reads = 0;     // non-finite device states, replaced by the last good one
  std::size_t part_resets = 0;          // non-finite part states, reset to the device state
  std::size_t passivity_frames = 0;     // frames in which the passivity controller damped the part
  double passivity_dissipated_j = 0;    // energy its damping removed, J
  std::size_t rate_limited_frames = 0;  // frames the force-rate bound damped the part
  double rate_limit_dissipated_j = 0;   // energy that damping removed, J
  std::size_t rate_slewed_frames = 0;   // frames whose sent force was slewed (paid from that energy)
  double rate_slew_work_j = 0;          // net work the slewed force's offset did on the hand, J
  std::size_t late_wakeup_misses = 0;   // misses whose own work fit: the thread woke late
  std::size_t stall_misses = 0;         // misses whose work was far beyond the model (ModePolicy::stall_factor)
  BodyState final_part;                 // after the last frame's step
  std::size_t final_modes = 0;
  double miss_rate() const { return frames ? double(misses) / frames : 0; }
};

// The counts of `end` less those of `start` (two snapshots of one loop, start earlier):
// rates, final part and m' from `end`.
LoopCounts counts_between(const LoopCounts& start, const LoopCounts& end);

struct LoopReport : LoopCounts {
  std::vector<double> frame_ms;         // every frame: tick to wrench sent (keep_frame_times)
  std::vector<double> wake_late_ms;     // every frame: FrameRecord::wake_late_ms (keep_frame_times)
  std::vector<FrameRecord> log;         // when keep_log
  std::vector<ModeChange> mode_changes;
};

// Runs the loop on the calling thread until duration or stop. The evaluator is set to
// the top level of the ladder first. Throws snapfit::Error for an invalid config.
LoopReport run_haptic_loop(HapticDevice& device, const WrenchEvaluator& engine, const LoopConfig& config,
                           const LoopClock& clock, BodyState part);

// The loop's view of a query engine: its query, and its set_modes.
WrenchEvaluator wrench_evaluator(QueryEngine& engine);

// The loop's configuration from the assembly's scene: rate, frame budget, the virtual
// coupling from its `haptics` section (inertia from part 2's mesh), the geometric gain
// calibrated with `engine` at the tuned m' (the force two grid spacings off the
// assembled pose), and the mode ladder and cost model of `tuning`. duration_s is the
// trajectory's length plus haptics.settle_s (0 without a trajectory: run until stopped).
// Leaves `engine` at the tuned m'. Throws snapfit::Error when the haptics cannot be set up.
LoopConfig loop_config(const Assembly& assembly, QueryEngine& engine, const TuningResult& tuning);

// The same on its own thread (what a haptics program does); join() returns the report.
class HapticLoopThread {
 public:
  HapticLoopThread(HapticDevice& device, WrenchEvaluator engine, LoopConfig config, BodyState part,
                   LoopClock clock = steady_loop_clock());
  ~HapticLoopThread();
  HapticLoopThread(const HapticLoopThread&) = delete;
  HapticLoopThread& operator=(const HapticLoopThread&) = delete;
  void request_stop() { stop_ = true; }
  LoopReport join();  // rethrows an exception from the loop

 private:
  struct State;
  std::unique_ptr<State> state_;
  std::atomic<bool> stop_{false};
};

}  // namespace snapfit
