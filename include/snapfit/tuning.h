#pragma once
// Auto-tuning of m' (docs/design.md "Auto-tuning"): the per-query time measured against
// m' on a ladder of mode counts (p99 over many paced repetitions, not the mean), a cost
// model fitted to it, and the largest m' whose p99 fits the scene's frame budget with a
// safety margin. Results are kept per machine in the tuning file, keyed by device,
// driver, kernel variant and scene features, and reused while the key matches.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "snapfit/query.h"

namespace snapfit {

class Assembly;
class QueryEngine;

struct TimingPoint {
  std::size_t modes = 0;
  double p50_ms = 0, p99_ms = 0, max_ms = 0;
  std::size_t samples = 0;
};

// p99(m') ~ fixed_ms + per_mode_ms * m', least squares over the measured p99 values.
struct CostModel {
  double fixed_ms = 0;
  double per_mode_ms = 0;
  double predict_ms(std::size_t modes) const { return fixed_ms + per_mode_ms * static_cast<double>(modes); }
};

struct TuningResult {
  std::vector<TimingPoint> points;  // by increasing m'
  CostModel model;
  std::size_t chosen_modes = 0;
  bool fits = false;  // the chosen m' meets the budget with margin
  double budget_ms = 0, margin = 0;
  std::string created;  // UTC date and time of the measurement
  std::string file;     // the tuning file it was read from or saved to (auto_tune); "" when not kept (nothing fits)
  double target_ms() const { return budget_ms * (1.0 - margin); }
};

// The result as the JSON text the tuning file keeps (points, model, chosen m', budget).
std::string tuning_to_json(const TuningResult& result);

// The tuning table, as `snapfit tune` and `snapfit run` print it: one line per m' level,
// then the target and the chosen m'.
std::string tuning_table(const TuningResult& tuning);

struct AutoTuneOptions {
  double margin = 0.25;           // keep p99 at most (1 - margin) of the frame budget
  bool retune = false;            // measure even when the tuning file matches
  std::size_t repetitions = 400;  // timed queries per m' level
  std::function<void(std::uint64_t done, std::uint64_t total)> progress;
  std::function<void(const std::string&)> note;  // a tuning file that could not be saved
};

// m' for the assembly's frame budget on its device, for `engine`'s variant, timed at the
// scene's loop rate along its trajectory (else at part 2's pose). Leaves the engine at
// the m' it had. Throws snapfit::Error when the engine cannot be timed.
TuningResult auto_tune(const Assembly& assembly, QueryEngine& engine, const AutoTuneOptions& options = {});

// The query strategy the loop should render on the assembly's device: of the
// interpolated sums (tricubic, trilinear) and the exact-rotation product, each tuned for
// the frame budget, the one with the lowest error of the rendered wrench (force and
// torque against the exact reference along the trajectory) among those that fit, as
// `snapfit run` chooses it. Measured once per scene, device and budget (tens of seconds
// on a CPU), then read from the strategy file. Make the loop's engine with it
// (Assembly::make_query_engine) and auto_tune that engine. Throws snapfit::Error when a
// strategy cannot be measured.
QueryVariant most_accurate_strategy(const Assembly& assembly, const AutoTuneOptions& options = {});

}  // namespace snapfit
