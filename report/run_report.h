#pragma once
// The report folder `snapfit run` writes (results/<scene>/): both parts as STL, a slice
// of each part's affinity through y = 0 of its frame (seed 000 Fig. 2 style), the tuning
// sweep, the haptic loop's log and charts (report/haptic_report.h), and summary.json.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

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

// Writes every file into `out` (created); returns their names, summary.json first.
// Throws snapfit::Error naming the file that cannot be written.
std::vector<std::string> write_run_report(const std::filesystem::path& out, const RunRecord& run);

}  // namespace snapfit
