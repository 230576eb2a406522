// `snapfit accuracy SCENE [--budget MS] [--device D]`: what the frame budget buys for this
// scene on this machine. Picks the loop's device as `snapfit run` does (or the one named),
// tunes each query strategy for the budget there, times it, and compares it with the
// exact-rotation reference at the trajectory's poses (include/snapfit/accuracy.h). Prints one
// JSON object on stdout: the loop's strategy at the top level, every strategy under
// "strategies", and which one has the lowest error within the budget.
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "report/accuracy_json.h"
#include "report/chart_spec.h"
#include "report/strategy_chart.h"
#include "report/web_assets.h"
#include "snapfit/accuracy.h"
#include "snapfit/assembly.h"
#include "snapfit/devices.h"
#include "snapfit/error.h"
#include "snapfit/progress.h"

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
  std::string html;  // a chart page of the strategies' errors against their frame time
};

// The report as one JSON object: the loop's strategy at the top level, every strategy
// under "strategies".
nlohmann::json accuracy_json(const AccuracyCommandOptions& opt, const Scene& scene, double budget,
                             const BudgetAccuracy& measured) {
  const AccuracyReport& report = measured.report;
  nlohmann::json j = strategy_accuracy_json(report.strategies[report.loop]);
  j["scene"] = opt.scene;
  j["device"] = measured.device;
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
  j["strategy_file"] = measured.strategy_file;
  return j;
}

void run_accuracy(const AccuracyCommandOptions& opt) {
  const Scene scene = load_scene(opt.scene);
  const double budget = opt.budget_ms.value_or(scene.frame_budget_ms);
  if (!(budget > 0)) throw Error("--budget: must be > 0 ms");
  if (opt.poses < 2) throw Error("--poses: at least 2");
  for (double w : opt.turning_deg_per_s)
    if (!(std::isfinite(w) && w >= 0)) throw Error("--turning: speeds must be >= 0 deg/s");
  if (!opt.html.empty()) web_asset("chart_page.js");  // a build without the web report fails before measuring
  const auto note = [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  AssemblyOptions assembly_options;
  assembly_options.device = opt.device;
  assembly_options.progress = true;
  assembly_options.note = note;
  assembly_options.near_field = true;  // the near-far strategy is measured beside the others
  const Assembly assembly(scene, assembly_options);

  BudgetAccuracyRequest request;
  request.budget_ms = budget;
  request.margin = opt.margin;
  request.poses = opt.poses;
  request.repetitions = opt.repetitions;
  request.retune = opt.retune;
  request.turning_deg_per_s = opt.turning_deg_per_s;
  // The loop's device, as `snapfit run` picks it: the one named, else the best tuned.
  request.other_devices = !names_device(opt.device);
  request.note = note;
  request.progress = pass_progress_bars();
  const BudgetAccuracy measured = measure_budget_accuracy(assembly, request);
  if (!opt.html.empty()) {
    const AccuracyReport& r = measured.report;
    write_chart_page(opt.html, "snapfit accuracy: " + scene.name,
                     {"device " + measured.device + ", " + std::to_string(r.poses) +
                          " poses along the trajectory, against the exact-rotation product over every mode",
                      "chosen: " + r.strategies[r.best].name + " (" + r.why + ")"},
                     {strategy_chart(r.strategies, budget)});
    std::cerr << "chart page " << opt.html << "\n";
  }
  std::cout << accuracy_json(opt, scene, budget, measured).dump() << std::endl;
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
  cmd->add_option("--html", opt->html,
                  "Also write a self-contained page charting each strategy's error against its frame time");
  cmd->callback([opt] { run_accuracy(*opt); });
}

}  // namespace snapfit::cli
