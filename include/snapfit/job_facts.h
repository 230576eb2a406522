#pragma once
// What a job built and measured, as plain data: the parts, their fields, the session's
// set-up and its end, the rigid contact, the Voxmap PointShell peer's build. JobResult
// (include/snapfit/job.h) carries them; `snapfit run`'s report folder and `snapfit
// serve`'s page are drawn from them alone.
#include <array>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>

#include "snapfit/fields.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/inspect.h"
#include "snapfit/mesh.h"
#include "snapfit/pose.h"

namespace snapfit {

// What the user feels at a pose: along +x, -x, +y, -y, +z, -z of part 1's frame, how much
// harder the rendered force pushes back when part 2 moves that way (N / mm, by one-sided
// differences over step_mm), and the torque when it turns about that axis (N m / degree,
// over tilt_deg), beside the coupling's own stiffness.
struct RenderedStiffness {
  double step_mm = 0.1;
  double tilt_deg = 0.2;
  std::array<double, 6> force_n_per_mm{};
  std::array<double, 6> torque_nm_per_deg{};
  double coupling_n_per_mm = 0, coupling_nm_per_deg = 0;
};

// What raising the loop's threads' priority did.
struct ThreadPriority {
  int threads = 0;     // threads whose priority was raised
  int realtime = 0;    // of those, threads now SCHED_FIFO (the others got the nice value)
  int failed = 0;      // threads it could not change (no CAP_SYS_NICE, or gone)
  std::string reason;  // why some failed
  int realtime_priority = 0, nice_value = 0;
  std::string describe() const;  // e.g. "SCHED_FIFO 10 for 4 threads" or "nice -10 for 4 threads"
};

// The rigid contact the loop adds to the engine's wrench: part 2's surface samples
// pressed against part 1's distance field.
struct RigidContactFacts {
  double pressure_stiffness_n_per_mm3 = 0;
  double sample_spacing = 0;    // between part 2's samples, scene units
  double distance_spacing = 0;  // of part 1's fine distance field, scene units
  double skin = 0;              // the depth over which the pressure builds, scene units
  std::size_t part1_edge_points = 0, part2_points = 0;
};

// A session's set-up (coupling, gain, bounds, contact) and its end judged against the
// target; the loop's own log is JobResult::loop.
struct SessionFacts {
  CouplingParams coupling;
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
  ThreadPriority priority;
  std::optional<RigidContactFacts> rigid_contact;  // absent: the loop rendered no rigid contact
  double contact_build_s = 0;
  std::string contact_off;      // why the scene's rigid contact is off (a part not watertight); empty otherwise
  double contact_ms = 0;        // its measured time per frame, reserved from the budget
  std::size_t start_modes = 0;  // the m' the loop started at: the tuned m' less the contact's share
  std::optional<RenderedStiffness> fit_stiffness;  // at the assembled pose, when the scene has one
  LoopWait wait = LoopWait::spin;
};

// "assembled", "not assembled", or "not evaluated (no assembled pose)".
std::string session_verdict(const SessionFacts& session);

// The end of the run in words: the signed axial and the lateral error, the angle and the
// force still sent, e.g. "axial +0.375 mm (past the fit), lateral 0.021 mm, 0.04 deg;
// 0.30 N sent".
std::string final_error_text(const SessionFacts& session, const std::string& units);

// What a Voxmap PointShell run built (Faas 2010; method "vps" or "vps_hybrid").
struct VpsFacts {
  double voxel_size = 0, shell_spacing = 0;  // scene units
  std::size_t surface_voxels = 0, interior_voxels = 0, proximity_voxels = 0, shell_points = 0;
  double stiffness_n_per_m = 0, braking_n_s_per_m = 0;
  double build_seconds = 0;
  // "method": "vps_hybrid": whether it ran as the hybrid, or why it ran as plain VPS.
  bool hybrid = false;
  std::string plain_reason;
  std::size_t faces1 = 0, faces2 = 0;                    // analytic faces of each part
  std::size_t labelled_voxels = 0, labelled_points = 0;  // on one face (not an edge, not none)
  double alignment_k_n_per_m = 0;
};

// One part as the job built it. The mesh and fields are shared with the job's engine (no
// copy); they stay valid as long as the result does.
struct JobPart {
  std::shared_ptr<const Mesh> mesh;                // in the part's own frame, scene units
  MeshReport report;                               // its size, box, volume, watertightness
  std::optional<CadFacts> cad;                     // what the import did, for a STEP or IGES part
  std::shared_ptr<const PartFieldsResult> fields;  // its descriptor fields; null for the VPS peer
};

}  // namespace snapfit
