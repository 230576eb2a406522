// `snapfit accuracy SCENE [--budget MS] [--device D]`: what the frame budget buys for this
// scene on this machine. Picks the loop's device as `snapfit run` does (or the one named),
// tunes each query strategy for the budget there, times it, and compares it with the
// exact-rotation reference at the trajectory's poses (scheduler/accuracy.h). Prints one
// JSON object on stdout: the loop's strategy at the top level, every strategy under
// "strategies", and which one has the lowest error within the budget.
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "core/progress.h"
#include "pipeline/assembly_pair.h"
#include "report/accuracy_json.h"
#include "scheduler/accuracy.h"
#include "scheduler/loop_devices.h"
#include "scheduler/query_strategy.h"
#include "scheduler/strategy_file.h"
#include "snapfit/error.h"

namespace snapfit::cli {
namespace {

struct AccuracyCommandOptions {
  std::string scene;
  std::string device;
  std::optional<double> budget_ms;
  double margin = 0.25;
  std::size_t poses = 24;
  std::size_t repetitions = 400;
  bool retune = false;
  std::vector<double> turning_deg_per_s = {0, 30, 90, 180};
};

void run_accuracy(const AccuracyCommandOptions& opt) {
  const Scene scene = load_scene(opt.scene);
  const double budget = opt.budget_ms.value_or(scene.frame_budget_ms);
  if (!(budget > 0)) throw Error("--budget: must be > 0 ms");
  if (opt.poses < 2) throw Error("--poses: at least 2");
  const auto note = [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  const Device device = select_device(device_spec_from(opt.device));
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(device);
  PairOptions pair_options;
  pair_options.descriptors.progress = pass_progress_bars();
  pair_options.note = note;
  const AssemblyPair pair = build_assembly_pair(scene, ctx, fft, pair_options);

  // The loop's device, as `snapfit run` picks it (the named one, else the best tuned).
  LoopDeviceOptions loop_options;
  loop_options.margin = opt.margin;
  loop_options.retune = opt.retune;
  loop_options.other_devices = device_spec_from(opt.device).empty();
  loop_options.note = note;
  const auto bars = pass_progress_bars();
  loop_options.tune.progress = [bars](std::uint64_t done, std::uint64_t total) { bars("tuning m'", done, total); };
  Scene timed = scene;
  timed.frame_budget_ms = budget;
  const LoopDevices devices =
      tune_loop_devices(ctx, timed, pair.spectra, query_variant_for(scene, Interpolation::tricubic), loop_options);
  const ComputeContext& loop_ctx = devices.loop().ctx;

  AccuracyOptions options;
  options.budget_ms = budget;
  options.margin = opt.margin;
  options.poses = opt.poses;
  options.retune = opt.retune;
  options.repetitions = opt.repetitions;
  for (double w : opt.turning_deg_per_s)
    if (!(std::isfinite(w) && w >= 0)) throw Error("--turning: speeds must be >= 0 deg/s");
  options.turning_deg_per_s = opt.turning_deg_per_s;
  options.note = note;
  options.progress = pass_progress_bars();
  const AccuracyReport report = measure_accuracy(loop_ctx, scene, pair.spectra, options);
  // `snapfit run` renders what this measured (scheduler/query_strategy.h).
  Scene at_budget = scene;
  at_budget.frame_budget_ms = budget;
  const std::string key = strategy_key(loop_ctx.device.info, at_budget, pair.spectra, options);
  try {
    save_strategy(key, report);
  } catch (const Error& e) {
    note(std::string("the strategy was not saved: ") + e.what());
  }

  const StrategyAccuracy& loop = report.strategies[report.loop];
  nlohmann::json j = strategy_accuracy_json(loop);
  j["scene"] = opt.scene;
  j["device"] = loop_ctx.device.info.name;
  j["budget_ms"] = budget;
  j["margin"] = opt.margin;
  j["poses"] = report.poses;
  j["reference"] = {{"method", scene.motion == Motion::translation ? "translation lines, every mode"
                                                                   : "exact-rotation product, every mode, "
                                                                     "made for each pose's rotation"},
                    {"modes", report.reference_modes},
                    {"seconds", report.reference_seconds}};
  j["error_definition"] = "sqrt(sum |x - x_ref|^2) / sqrt(sum |x_ref|^2) over the poses";
  nlohmann::json all = nlohmann::json::array();
  for (const StrategyAccuracy& s : report.strategies) all.push_back(strategy_accuracy_json(s));
  j["strategies"] = all;
  j["lowest_error_within_budget"] = report.strategies[report.best].name;
  j["why"] = report.why;
  j["strategy_file"] = strategy_file_path(key);
  std::cout << j.dump() << std::endl;
}

}  // namespace

void add_accuracy_command(CLI::App& app) {
  auto opt = std::make_shared<AccuracyCommandOptions>();
  CLI::App* cmd = app.add_subcommand(
      "accuracy", "What the frame budget buys: m', frame time and error against an exact-rotation reference (JSON)");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option("--budget", opt->budget_ms, "Frame budget in ms (default: the scene's frame.budget_ms)");
  cmd->add_option("--margin", opt->margin, "Safety margin: p99 at most (1 - margin) of the budget")
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_option("--device", opt->device, "OpenCL device (see `snapfit devices`; default: the loop's pick)");
  cmd->add_option("--poses", opt->poses, "Reference poses along the trajectory (default 24)");
  cmd->add_option("--repetitions", opt->repetitions, "Timed queries per m' level and at the chosen m'")
      ->check(positive_number());
  cmd->add_flag("--retune", opt->retune, "Measure m' even when the tuning file matches");
  cmd->add_option("--turning", opt->turning_deg_per_s,
                  "Angular speeds (deg/s) at which the exact product with background updates is also measured "
                  "while part 2 turns (0.2 s at the loop rate from 6 poses)")
      ->delimiter(',');
  cmd->callback([opt] { run_accuracy(*opt); });
}

}  // namespace snapfit::cli
