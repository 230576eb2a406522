// measure_budget_accuracy (include/snapfit/accuracy.h): the loop's device picked and
// tuned as the haptic loop does (scheduler/tuning/loop_devices.h), the strategies measured there
// (scheduler/tuning/accuracy.h), and the report saved in the strategy file
// (scheduler/tuning/strategy_file.h) that most_accurate_strategy reads.
#include <cmath>

#include "pipeline/assembly_access.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/tuning/accuracy.h"
#include "scheduler/tuning/loop_devices.h"
#include "scheduler/tuning/query_strategy.h"
#include "scheduler/tuning/strategy_file.h"
#include "snapfit/accuracy.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

void check_request(const BudgetAccuracyRequest& request, double budget) {
  if (!(budget > 0)) throw Error("accuracy: the frame budget must be > 0 ms");
  if (request.poses < 2) throw Error("accuracy: at least 2 poses");
  for (double w : request.turning_deg_per_s)
    if (!(std::isfinite(w) && w >= 0)) throw Error("accuracy: turning speeds must be >= 0 deg/s");
}

AccuracyOptions accuracy_options(const BudgetAccuracyRequest& request, double budget) {
  AccuracyOptions options;
  options.budget_ms = budget;
  options.margin = request.margin;
  options.poses = request.poses;
  options.retune = request.retune;
  options.repetitions = request.repetitions;
  options.turning_deg_per_s = request.turning_deg_per_s;
  options.note = request.note;
  options.progress = request.progress;
  return options;
}

}  // namespace

BudgetAccuracy measure_budget_accuracy(const Assembly& assembly, const BudgetAccuracyRequest& request) {
  const Scene& scene = assembly.scene();
  const PairSpectra& spectra = AssemblyAccess::pair(assembly).spectra;
  const double budget = request.budget_ms == 0 ? scene.frame_budget_ms : request.budget_ms;
  check_request(request, budget);

  LoopDeviceOptions loop_options;
  loop_options.margin = request.margin;
  loop_options.retune = request.retune;
  loop_options.other_devices = request.other_devices;
  loop_options.note = request.note;
  if (request.progress)
    loop_options.tune.progress = [&](std::uint64_t done, std::uint64_t total) {
      request.progress("tuning m'", done, total);
    };
  Scene at_budget = scene;
  at_budget.frame_budget_ms = budget;
  const LoopDevices devices = tune_loop_devices(AssemblyAccess::context(assembly), at_budget, spectra,
                                                query_variant_for(scene, Interpolation::tricubic), loop_options);
  const ComputeContext& loop_ctx = devices.loop().ctx;

  const AccuracyOptions options = accuracy_options(request, budget);
  BudgetAccuracy out;
  out.report = measure_accuracy(loop_ctx, scene, spectra, options);
  out.device = loop_ctx.device.info.name;
  const std::string key = strategy_key(loop_ctx.device.info, at_budget, spectra, options);
  out.strategy_file = strategy_file_path(key);
  try {
    save_strategy(key, out.report);
  } catch (const Error& e) {
    if (request.note) request.note(std::string("the strategy was not saved: ") + e.what());
  }
  return out;
}

}  // namespace snapfit
