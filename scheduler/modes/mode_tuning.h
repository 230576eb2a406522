#pragma once
// Tuning m' (include/snapfit/tuning.h; docs/design.md "Auto-tuning"): measure the per-query time against m'
// on a ladder of mode counts (many repetitions each; p99, not the mean), fit a cost
// model, and pick the largest m' whose p99 fits the frame budget with a safety margin.
//
// The pick: the largest ladder level whose measured p99 AND model prediction are both
// at most budget * (1 - margin); the measured value guards against a model that fits
// badly, the model against one noisy measurement. Nothing beyond the largest measured
// level is extrapolated. When even the smallest level does not fit, it is chosen and
// `fits` is false. A level whose p99 misses the target is timed a second time and the
// lower p99 kept, so one burst of other work on the machine neither ends the sweep nor
// lowers the pick.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "snapfit/tuning.h"

namespace snapfit {

CostModel fit_cost_model(const std::vector<TimingPoint>& points);

struct TuneOptions {
  double budget_ms = 1.0;
  double margin = 0.25;  // keep p99 at most (1 - margin) of the budget
  std::size_t min_modes = 512;
  double ladder_factor = 1.41421356;  // sqrt(2) between levels
  std::size_t repetitions = 400;      // timed queries per level
  std::size_t warmup = 20;            // untimed queries per level first
  // The sweep stops after the first level whose p99 exceeds this multiple of the target.
  double stop_factor = 1.5;
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
};

// m' levels from min_modes to max_modes, multiplying by `factor` (rounded to
// multiples of 64), always ending at max_modes.
std::vector<std::size_t> mode_ladder(std::size_t min_modes, std::size_t max_modes, double factor);

// Choose from measured points (see the header comment). Throws snapfit::Error when empty.
TuningResult pick_modes(std::vector<TimingPoint> points, double budget_ms, double margin);

// Times `count` queries at m' = modes; returns each one's time in ms.
using QueryTimer = std::function<std::vector<double>(std::size_t modes, std::size_t count)>;

// Measures the ladder up to max_modes with `timer` and picks m'.
TuningResult tune_modes(const QueryTimer& timer, std::size_t max_modes, const TuneOptions& options);

// The ladder the haptic loop steps along: the measured levels up to the chosen m'.
std::vector<std::size_t> loop_levels(const TuningResult& tuning);

}  // namespace snapfit
