#pragma once
// What `snapfit run` knows at the end of its job, for the report (report/run_report.h).
#include <optional>
#include <string>

#include "engine/device.h"
#include "engine/device_check.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/assembly_session.h"
#include "scheduler/auto_tune.h"

namespace snapfit {

struct RunRecord {
  const AssemblyPair* pair = nullptr;  // parts, fields, spectra
  DeviceInfo device;                   // where fields and spectra were computed
  DeviceInfo loop_device;              // where the loop ran (or would run)
  DeviceCheckResult check;
  TuningResult tuning;
  std::string tuning_key;                // "" when m' was fixed by the user
  std::optional<SessionResult> session;  // the scripted assembly, when the scene has a trajectory
  double seconds = 0;                    // the whole job so far
};

}  // namespace snapfit
