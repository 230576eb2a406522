// `snapfit tune SCENE [--budget MS]`: measures per-query time against m' on the chosen
// device for the scene's query variant (include/snapfit/tuning.h), prints the table, saves
// the tuning file that `snapfit run` reuses, and writes a page with a chart of the sweep.
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "report/chart_spec.h"
#include "report/haptic_report.h"
#include "report/web_assets.h"
#include "snapfit/assembly.h"
#include "snapfit/devices.h"
#include "snapfit/error.h"
#include "snapfit/progress.h"
#include "snapfit/tuning.h"

namespace snapfit::cli {
namespace {

struct TuneCommandOptions {
  std::string scene;
  std::string device;
  std::optional<double> budget_ms;
  double margin = 0.25;
  std::size_t repetitions = 400;
  std::string interpolation = "tricubic";
  std::string html;
};

void run_tune(const TuneCommandOptions& opt) {
  Scene scene = load_scene(opt.scene);
  const double budget = opt.budget_ms.value_or(scene.frame_budget_ms);
  if (!(budget > 0)) throw Error("--budget: must be > 0 ms");
  if (!opt.html.empty()) web_asset("chart_page.js");  // a build without the web report fails before measuring
  const DeviceInfo device = find_device(opt.device);
  std::cout << "device " << describe_device(device) << "\n";
  scene.frame_budget_ms = budget;  // what auto_tune tunes for
  AssemblyOptions assembly_options;
  assembly_options.device = opt.device;
  assembly_options.progress = true;
  const Assembly assembly(scene, assembly_options);
  const QueryVariant variant = assembly.query_variant(parse_interpolation(opt.interpolation));
  auto engine = assembly.make_query_engine(variant);
  std::cout << "variant " << variant_name(variant) << ", " << engine->max_modes() << " modes available, budget "
            << budget << " ms, margin " << opt.margin * 100 << " %\n";

  AutoTuneOptions tune;
  tune.margin = opt.margin;
  tune.retune = true;
  tune.repetitions = opt.repetitions;
  const auto bars = pass_progress_bars();  // one bar, finished when the sweep ends
  tune.progress = [bars](std::uint64_t done, std::uint64_t total) { bars("tuning m'", done, total); };
  tune.note = [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  const TuningResult tuned = auto_tune(assembly, *engine, tune);
  std::cout << tuning_table(tuned)
            << (tuned.file.empty() ? "not saved: no m' fits the budget (the next run measures again)"
                                   : "saved to " + tuned.file)
            << "\n";
  if (!opt.html.empty()) {
    write_chart_page(opt.html, "snapfit tune: " + scene.name,
                     {"Scene " + scene.source_path + ", device " + device.name + ", " + variant_name(variant) +
                      ", measured " + tuned.created},
                     {tuning_chart(tuned, device.name)});
    std::cout << "chart page " << opt.html << "\n";
  }
}

}  // namespace

void add_tune_command(CLI::App& app) {
  auto opt = std::make_shared<TuneCommandOptions>();
  CLI::App* cmd =
      app.add_subcommand("tune", "Measure query time against m' and pick m' for the frame budget (saved per device)");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option("--budget", opt->budget_ms, "Frame budget in ms (default: the scene's frame.budget_ms)");
  cmd->add_option("--margin", opt->margin, "Safety margin: p99 at most (1 - margin) of the budget")
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_option("--repetitions", opt->repetitions, "Timed queries per m' level")->check(positive_number());
  cmd->add_option("--interpolation", opt->interpolation, "trilinear or tricubic (what `snapfit run` uses: tricubic)");
  cmd->add_option("--device", opt->device, "OpenCL device (see `snapfit devices`)");
  cmd->add_option("--html", opt->html, "Write a self-contained page with a chart of the sweep");
  cmd->callback([opt] { run_tune(*opt); });
}

}  // namespace snapfit::cli
