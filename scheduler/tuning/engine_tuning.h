#pragma once
// Auto-tuning of a QueryEngine on its device (scheduler/modes/mode_tuning.h), with the
// result kept in the tuning file (scheduler/modes/tuning_file.h) and reused while the key
// (device, driver, kernel variant, scene features, budget, margin) is unchanged.
#include <functional>
#include <string>
#include <vector>

#include "engine/runtime/device.h"
#include "engine/spectra/spectra.h"
#include "scheduler/modes/mode_tuning.h"
#include "scheduler/modes/tuning_file.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

// pace_hz: the rate queries are timed at (the scene's loop rate; 0: back-to-back).
TuningKey tuning_key_for(const DeviceInfo& device, const QueryVariant& variant, const PairSpectra& spectra,
                         double budget_ms, double margin, double pace_hz);

// Times single queries of `engine` at the given poses (cycled), wall clock around each.
// With pace_hz > 0 the queries are issued on absolute deadlines at that rate, idle in
// between, as in the haptic loop: an OpenCL runtime whose worker threads fall asleep
// between frames shows its wake-up cost here, which back-to-back queries would hide.
QueryTimer engine_query_timer(QueryEngine& engine, std::vector<Pose> poses, double pace_hz = 0);

// The poses the tuner times queries at: the scene's trajectory at 100 Hz, else part 2's pose.
std::vector<Pose> tuning_poses(const Scene& scene);

struct EngineTuning {
  TuningResult result;
  bool from_file = false;
  bool saved = false;  // measured and written to `path` (false when read, or when nothing fits)
  std::string path;
};

// Loads the tuning for `key`, or (when absent, stale, corrupt, or `retune`) measures it
// with `timer` and saves it: unless not even the smallest m' fits (said through `note`;
// the next run measures again). A save failure is reported through `note` and the fresh
// result is still returned.
EngineTuning tune_and_keep(const TuningKey& key, const QueryTimer& timer, std::size_t max_modes, TuneOptions options,
                           bool retune, const std::function<void(const std::string&)>& note);

// tune_and_keep with `engine` at `poses`; the engine's m' is left as it was.
// The queries are paced at key.pace_hz (engine_query_timer; 0: back-to-back).
EngineTuning tune_engine(QueryEngine& engine, const TuningKey& key, const std::vector<Pose>& poses, TuneOptions options,
                         bool retune, const std::function<void(const std::string&)>& note);

}  // namespace snapfit
