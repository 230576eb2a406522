#pragma once
// Which query strategy the loop renders: the one with the lowest error of the rendered
// wrench that fits the frame on the loop's device (scheduler/tuning/accuracy.h), measured once
// per scene, device and budget and then read from the strategy file
// (scheduler/tuning/strategy_file.h). On a GPU that is the exact-rotation product over as many
// modes as the frame allows; on a CPU whichever of the interpolated sums and the product
// is more accurate at the m' each affords.
#include <functional>
#include <optional>
#include <string>

#include "engine/runtime/compute_context.h"
#include "engine/spectra/spectra.h"
#include "scheduler/tuning/accuracy.h"
#include "snapfit/scene.h"

namespace snapfit {

struct StrategyChoice {
  AccuracyReport report;
  bool from_file = false;
  std::string path;  // the strategy file
  const StrategyAccuracy& chosen() const { return report.strategies[report.best]; }
};

// The strategy file's key on `device` for `scene`, `spectra` and `options` (budget,
// margin, poses): every candidate's tuning key.
std::string strategy_key(const DeviceInfo& device, const Scene& scene, const PairSpectra& spectra,
                         const AccuracyOptions& options);

// The choice kept in the strategy file, or nothing (absent, stale, corrupt, or
// options.retune): nothing is measured.
std::optional<StrategyChoice> stored_query_strategy(const ComputeContext& ctx, const Scene& scene,
                                                    const PairSpectra& spectra, const AccuracyOptions& options);

// Reads the choice from the strategy file, or (absent, stale, corrupt, or
// options.retune) measures it with measure_accuracy on ctx's device and saves it; a save
// failure is reported through options.note and the fresh choice still returned.
StrategyChoice choose_query_strategy(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                                     const AccuracyOptions& options);

}  // namespace snapfit
