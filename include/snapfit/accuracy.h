#pragma once
// What a frame budget buys for a scene on this machine (docs/design.md "Auto-tuning"):
// the loop's device picked as the haptic loop picks it, each query strategy tuned for the
// budget there (include/snapfit/tuning.h), its per-frame time, and its error against a
// reference that is exact in rotation (every mode of the exact-rotation product, made for
// each pose's own rotation) at poses along the scene's trajectory. The result is kept in
// the strategy file that most_accurate_strategy reads.
//
// Error of a quantity x over the poses: sqrt(sum |x - x_ref|^2) / sqrt(sum |x_ref|^2).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "snapfit/query.h"

namespace snapfit {

class Assembly;

// The error of a strategy while part 2 turns (the exact product with background updates
// lags the rotation): relative errors as above at the end of 0.2 s of queries at the loop
// rate along a rotation at `deg_per_s`.
struct TurningAccuracy {
  double deg_per_s = 0;
  double energy_error = 0, force_error = 0, torque_error = 0;
  // At the same final poses with the product made for each (no lag): the turning
  // ends elsewhere at each speed, so this is what each speed's errors compare with.
  double at_rest_energy_error = 0, at_rest_force_error = 0, at_rest_torque_error = 0;
};

struct StrategyAccuracy {
  std::string name;  // variant_name(): "6dof energy force torque tricubic", ...
  QueryVariant variant;
  std::size_t modes = 0;  // m' tuned for the budget
  bool fits = false;      // the tuner fitted its p99 within the margin, and the frame p99 below is within the budget
  double frame_ms_p50 = 0, frame_ms_p99 = 0;
  double energy_error = 0, force_error = 0, torque_error = 0;
  // The per-query error estimate (QueryResult::error_estimate) against the true error
  // |x - x_ref| at each pose, per output (0 energy, 1 force, 2 torque): the share of poses
  // where it is at least the true error, and the median of estimate / true error.
  double estimate_coverage[3] = {0, 0, 0};
  double estimate_ratio_median[3] = {0, 0, 0};
  // exact_product only: the time to make one product at `modes` (how far behind the
  // current rotation the background product can be); the errors above are with the
  // product made for each pose's rotation (a part at rest).
  double product_ms = 0;
  std::vector<TurningAccuracy> turning;  // exact_product with background updates, when asked for
};

// A strategy's name for people, short: "tricubic", "trilinear", "exact product",
// "exact product, near-far", "translation lines".
std::string strategy_short_name(const QueryVariant& variant);

struct AccuracyReport {
  std::size_t poses = 0;
  std::size_t reference_modes = 0;
  double reference_seconds = 0;
  std::vector<StrategyAccuracy> strategies;
  std::size_t best = 0;  // the lowest error of what the loop renders among the strategies that fit
  std::size_t loop = 0;  // the strategy the haptic loop uses: the best
  std::string why;       // in a few words: the rule the best won by, its error against the next best's
};

struct BudgetAccuracyRequest {
  double budget_ms = 0;           // the frame budget; 0: the scene's
  double margin = 0.25;           // keep p99 at most (1 - margin) of the budget
  std::size_t poses = 24;         // reference poses, evenly in time along the trajectory (at least 2)
  std::size_t repetitions = 400;  // timed queries per m' level and at the chosen m'
  bool retune = false;            // measure m' even when the tuning file matches
  // Angular speeds (deg/s) at which the exact product with background updates is also
  // measured while part 2 turns; none: only at rest.
  std::vector<double> turning_deg_per_s;
  // Also tune every other device that passes its self-check and measure on the loop's pick
  // (as the haptic loop chooses); false: the assembly's device.
  bool other_devices = true;
  std::function<void(const std::string& stage, std::uint64_t done, std::uint64_t total)> progress;
  std::function<void(const std::string&)> note;  // devices left out, files not saved
};

struct BudgetAccuracy {
  AccuracyReport report;
  std::string device;         // the loop's device, where the strategies were measured
  std::string strategy_file;  // where the report was saved for most_accurate_strategy
};

// Throws snapfit::Error for a budget that is not positive, fewer than 2 poses, a negative
// or non-finite turning speed, spectra that cannot carry a strategy's reference, or a
// device failure. A strategy file that cannot be written is reported through `note`.
BudgetAccuracy measure_budget_accuracy(const Assembly& assembly, const BudgetAccuracyRequest& request);

}  // namespace snapfit
