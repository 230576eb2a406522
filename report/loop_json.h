#pragma once
// The haptic loop's figures (include/snapfit/haptic_loop.h LoopReport) as JSON, shared by
// `snapfit run`'s summary and perf/bench_haptic_loop.
#include <nlohmann/json.hpp>

#include "snapfit/haptic_loop.h"

namespace snapfit {

// rate_hz, measured_rate_hz, elapsed_s, ticks, frames, misses (miss_rate, skipped_ticks,
// late_wakeup_misses, stall_misses), flagged_frames, and p50/p99/max of frame_ms and
// wake_late_ms.
nlohmann::json loop_json(const LoopReport& loop);

// Every change of m': time_s, frame, from, to, reason.
nlohmann::json mode_changes_json(const std::vector<ModeChange>& changes);

}  // namespace snapfit
