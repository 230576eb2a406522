#pragma once
// A scripted assembly session: the scene's trajectory played by a ScriptedDevice into
// the haptic loop, with the engine at the tuned m', the coupling and gain from the
// scene's `haptics` section, and the final pose judged against the assembled pose
// (scheduler/haptics/assembly_verdict.h). `snapfit run` and perf/bench_haptic_loop use it.
#include <optional>

#include "mesh/mesh.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/modes/mode_tuning.h"
#include "scheduler/haptics/rendered_wrench.h"
#include "scheduler/haptics/rigid_contact.h"
#include "scheduler/haptics/thread_priority.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

struct SessionOptions {
  std::optional<double> duration_s;  // default: the trajectory's length + haptics.settle_s
  bool loop_back = false;            // replay the trajectory back and forth (long runs)
  bool keep_log = true;
  bool simulated_time = false;  // snapfit/haptic_loop.h simulated_loop_clock (deterministic)
  // How the loop waits for its tick (snapfit/haptic_loop.h LoopWait).
  LoopWait wait = LoopWait::spin;
  // The run's threads during the loop (scheduler/haptics/thread_priority.h), restored after it:
  // nice -20 when the loop spins; when it sleeps, SCHED_FIFO 10 where allowed, else nice
  // -20. {0, 0} leaves them.
  PriorityRequest priority{-20, 10};
  int warmup_queries = 50;  // queries at the first pose before the loop starts
  // The rigid contact's time the frame reserves for it (ms), when measured already (the
  // main job measures it before choosing the strategy); else measured here.
  std::optional<double> contact_ms;
};

struct SessionResult {
  LoopReport loop;
  CouplingParams coupling;
  DeviceLimits limits;
  double geometry_gain = 0;
  double max_force_rate_n_per_s = 0;  // the loop's bound on the sent force's rate (0: none)
  double force_scale = 0;             // largest engine force at the gain's probe poses
  Pose target;                        // the assembled pose (else the last keyframe)
  PoseError final_error;
  // The final position error split along the insertion (the trajectory's last segment,
  // pointing into the fit) and across it, scene units: axial > 0 is past the target
  // (deeper than the fit), < 0 short of it.
  Eigen::Vector3d insertion_direction = Eigen::Vector3d::UnitZ();
  double axial_error = 0, lateral_error = 0;
  Eigen::Vector3d final_force = Eigen::Vector3d::Zero();  // sent to the device in the last frame, N
  // How far part 2's surface at the final pose lies from its surface at the target (the
  // two-sided Hausdorff distance, scene units; 0 for a round peg turned about its axis),
  // and the sample farthest off, in part 2's own frame.
  double surface_deviation = 0;
  Eigen::Vector3d surface_deviation_at = Eigen::Vector3d::Zero();
  double position_tolerance = 0;  // scene units
  double angle_tolerance_deg = 0;
  bool evaluated = false;  // the scene has an assembled pose to judge the end against
  // evaluated, and final_error within both tolerances or surface_deviation within the
  // position tolerance
  bool assembled = false;
  PriorityChange priority;                           // what raising the threads' priority did
  std::shared_ptr<const RigidContactModel> contact;  // null: the loop rendered no rigid contact
  double contact_build_s = 0;
  double setup_s = 0;           // from the call to the loop's first frame (contact, coupling, gain)
  std::string contact_off;      // why the scene's rigid contact is off (a part not watertight); empty otherwise
  double contact_ms = 0;        // its measured time per frame, reserved from the budget (LoopConfig::contact_ms)
  std::size_t start_modes = 0;  // the m' the loop started at: the tuned m' less the contact's share
  std::optional<RenderedStiffness> fit_stiffness;  // at the assembled pose, when the scene has one
  LoopWait wait = LoopWait::spin;
};

// The direction part 2 moves in at the end of `trajectory` (its last segment that moves),
// towards `target`; without one, from the first keyframe to the target (else +z).
Eigen::Vector3d insertion_direction(const Trajectory& trajectory, const Pose& target);

// Runs the loop on its own thread on the steady clock and waits for it. Throws
// snapfit::Error when the scene has no trajectory or its haptics cannot be set up.
// The scene's rigid contact (scheduler/haptics/rigid_contact.h) is built from both meshes and
// added to the engine's wrench unless the scene turns it off.
SessionResult run_scripted_assembly(const Scene& scene, const Mesh& part1_mesh, const Mesh& part2_mesh, double spacing,
                                    QueryEngine& engine, const TuningResult& tuning,
                                    const SessionOptions& options = {});

// A session's result before its loop runs: the scene's device limits, target (the
// assembled pose, else the last keyframe, else part 2's initial pose) and tolerances,
// and the loop's coupling, gain and bounds.
SessionResult session_before_loop(const Scene& scene, double spacing, const LoopConfig& config);

// After it (out.loop set): the final pose judged against the target (its pose and part
// 2's surface, scheduler/haptics/assembly_verdict.h), the error along and across the insertion,
// the last force sent. Throws snapfit::Error for an empty part 2 mesh.
void judge_session_end(SessionResult& out, const Scene& scene, const Mesh& part2_mesh);

// The threads' priority for a loop that waits by `wait`: no SCHED_FIFO for a spinning
// loop (the kernel throttles a real-time thread that never sleeps).
PriorityRequest loop_priority(const PriorityRequest& request, LoopWait wait);

// The same for any method's evaluator and loop configuration (a Voxmap PointShell run:
// scheduler/vps/vps_method.h); `spacing` is the default position tolerance; part 2's mesh
// is for the verdict.
SessionResult run_scripted_session(const Scene& scene, const Mesh& part2_mesh, double spacing, LoopConfig config,
                                   const WrenchEvaluator& evaluator, const SessionOptions& options = {});

}  // namespace snapfit
