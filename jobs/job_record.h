#pragma once
// Everything the main job (snapfit/job.h) built and measured, as the job's own steps
// keep it; job_result (jobs/job_steps.h) gives the public, plain-data JobResult from it.
#include <memory>
#include <optional>
#include <string>

#include "engine/runtime/device.h"
#include "engine/runtime/device_check.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/assembly_session.h"
#include "scheduler/modes/mode_tuning.h"
#include "scheduler/tuning/accuracy.h"
#include "snapfit/job_facts.h"  // VpsFacts

namespace snapfit {

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
