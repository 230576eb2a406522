#pragma once
// The tuning file: an auto-tuning result kept per machine in the cache folder
// (<cache root>/tuning/, io/cache_file.h: versioned, checksummed, written atomically),
// keyed by the device name, its driver version, the kernel variant and the scene
// features that change the query cost. A file for another key, a corrupt file or a
// missing one reads as absent (with the reason), so the caller re-tunes.
#include <functional>
#include <optional>
#include <string>

#include "scheduler/modes/mode_tuning.h"

namespace snapfit {

struct TuningKey {
  std::string platform;
  std::string device;
  std::string driver;
  std::string variant;         // e.g. "6dof force torque tricubic"
  std::string scene_features;  // e.g. "fft 128x96x96 max_modes 1179648"
  double budget_ms = 1.0;
  double margin = 0.25;
  double pace_hz = 0;        // queries timed at this rate (the loop's), 0: back-to-back
  std::string text() const;  // the full key, stored in the file
};

std::string tuning_file_path(const TuningKey& key);

// The result as JSON text (tuning_to_json, include/snapfit/tuning.h), and back (throws
// snapfit::Error on malformed text).
TuningResult tuning_from_json(const std::string& text);

// Absent when missing, stale (another key or format version) or corrupt; `note` hears why.
std::optional<TuningResult> load_tuning(const TuningKey& key,
                                        const std::function<void(const std::string&)>& note = nullptr);

// Throws snapfit::Error naming the path when the cache folder cannot be written.
void save_tuning(const TuningKey& key, const TuningResult& result);

}  // namespace snapfit
