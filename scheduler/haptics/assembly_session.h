#pragma once
// A scripted assembly session: the scene's trajectory played by a ScriptedDevice into
// the haptic loop, with the engine at the tuned m', the coupling and gain from the
// scene's `haptics` section, and the final pose judged against the assembled pose
// (scheduler/haptics/assembly_verdict.h). `snapfit run` and perf/bench_haptic_loop use it.
#include <optional>

#include "mesh/mesh.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/rendered_wrench.h"
#include "scheduler/haptics/rigid_contact.h"
#include "scheduler/haptics/thread_priority.h"
#include "scheduler/modes/mode_tuning.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/job_facts.h"
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

// The session's facts (include/snapfit/job_facts.h), its loop's log, and what the engine's
// side keeps: the device's limits, the rigid contact it rendered.
struct SessionResult : SessionFacts {
  LoopReport loop;
  DeviceLimits limits;
  std::shared_ptr<const RigidContactModel> contact;  // null: the loop rendered no rigid contact
  double setup_s = 0;  // from the call to the loop's first frame (contact, coupling, gain)
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
