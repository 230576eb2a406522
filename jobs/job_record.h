#pragma once
// Everything the main job (snapfit/job.h) built and measured, for the tool's report.
#include <memory>
#include <optional>
#include <string>

#include "engine/runtime/device.h"
#include "engine/runtime/device_check.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/tuning/accuracy.h"
#include "scheduler/haptics/assembly_session.h"
#include "scheduler/modes/mode_tuning.h"

namespace snapfit {

// What a Voxmap PointShell run built (scheduler/vps/vps_method.h).
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

struct JobRecord {
  std::shared_ptr<const AssemblyPair> pair;  // parts, fields, spectra
  DeviceInfo device;                         // where fields and spectra were computed
  DeviceInfo loop_device;                    // where the loop ran (or would run)
  DeviceCheckResult check;
  TuningResult tuning;
  std::string tuning_key;  // "" when m' was fixed by the user
  // The query strategy the loop renders and why (scheduler/tuning/query_strategy.h): the
  // measured candidates when it was chosen by error, else none.
  std::string strategy;        // variant_name() of the loop's engine
  std::string strategy_label;  // the same, short (strategy_short_name)
  std::string
      strategy_chosen_by;  // "lowest error that fits (measured)", "... (strategy file)", "JobRequest::strategy", "JobRequest::modes (not measured)"
  std::optional<AccuracyReport> strategies;  // the candidates, when chosen by error
  std::string strategy_file;                 // where the choice is kept
  std::optional<SessionResult> session;      // the scripted assembly, when the scene has a trajectory
  // The rigid contact the loop adds, and the frame time reserved for it before the
  // strategy and m' were chosen (scheduler/haptics/haptic_setup.h reserved_contact_ms); null / 0
  // without contact or with a fixed m'.
  std::shared_ptr<const RigidContactModel> contact;
  std::string contact_off;  // why the scene's contact is off (a part not watertight); empty otherwise
  double contact_reserved_ms = 0;
  double seconds = 0;                 // the whole job so far
  double seconds_to_first_frame = 0;  // from the job's start to the loop's first frame (0: no loop)
  std::optional<VpsFacts> vps;        // set for a scene whose method is "vps" (no fields, spectra or tuning)
};

}  // namespace snapfit
