#include "scheduler/tuning/query_strategy.h"

#include <sstream>

#include "pipeline/assembly_access.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/tuning/engine_tuning.h"
#include "scheduler/tuning/strategy_file.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/tuning.h"

namespace snapfit {

std::string strategy_key(const DeviceInfo& device, const Scene& scene, const PairSpectra& spectra,
                         const AccuracyOptions& options) {
  std::ostringstream key;
  key << "poses=" << options.poses;
  if (options.reserved_ms > 0) key << "\nreserved_ms=" << options.reserved_ms;
  for (const QueryVariant& v : accuracy_candidates(accuracy_base_variant(scene), spectra.near != nullptr))
    key << "\n--\n" << tuning_key_for(device, v, spectra, options.budget_ms, options.margin, scene.loop_rate_hz).text();
  return key.str();
}

std::optional<StrategyChoice> stored_query_strategy(const ComputeContext& ctx, const Scene& scene,
                                                    const PairSpectra& spectra, const AccuracyOptions& options) {
  if (options.retune) return std::nullopt;
  const std::string key = strategy_key(ctx.device.info, scene, spectra, options);
  std::optional<AccuracyReport> stored = load_strategy(key, accuracy_base_variant(scene), options.note);
  if (!stored) return std::nullopt;
  StrategyChoice choice;
  choice.path = strategy_file_path(key);
  choice.report = std::move(*stored);
  choice.from_file = true;
  return choice;
}

StrategyChoice choose_query_strategy(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                                     const AccuracyOptions& options) {
  if (std::optional<StrategyChoice> stored = stored_query_strategy(ctx, scene, spectra, options)) return *stored;
  StrategyChoice choice;
  const std::string key = strategy_key(ctx.device.info, scene, spectra, options);
  choice.path = strategy_file_path(key);
  choice.report = measure_accuracy(ctx, scene, spectra, options);
  try {
    save_strategy(key, choice.report);
  } catch (const Error& e) {
    if (options.note) options.note(std::string("the strategy was not saved: ") + e.what());
  }
  return choice;
}

QueryVariant most_accurate_strategy(const Assembly& assembly, const AutoTuneOptions& options) {
  AccuracyOptions accuracy;
  accuracy.budget_ms = assembly.scene().frame_budget_ms;
  accuracy.margin = options.margin;
  accuracy.retune = options.retune;
  accuracy.repetitions = options.repetitions;
  if (options.progress)
    accuracy.progress = [&](const std::string&, std::uint64_t done, std::uint64_t total) {
      options.progress(done, total);
    };
  return choose_query_strategy(AssemblyAccess::context(assembly), assembly.scene(),
                               AssemblyAccess::pair(assembly).spectra, accuracy)
      .chosen()
      .variant;
}

}  // namespace snapfit
