// `snapfit tune SCENE [--budget MS]`: measures per-query time against m' on the chosen
// device for the scene's query variant (scheduler/mode_tuning.h), prints the table, saves
// the tuning file that `snapfit run` reuses, and writes a page with a chart of the sweep.
#include <iostream>
#include <memory>
#include <optional>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "core/progress.h"
#include "engine/runtime/device.h"
#include "engine/query/query_engine.h"
#include "pipeline/assembly_pair.h"
#include "report/chart_spec.h"
#include "report/haptic_report.h"
#include "report/web_assets.h"
#include "scheduler/engine_tuning.h"
#include "scheduler/loop_devices.h"
#include "snapfit/error.h"

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
  const Scene scene = load_scene(opt.scene);
  const double budget = opt.budget_ms.value_or(scene.frame_budget_ms);
  if (!(budget > 0)) throw Error("--budget: must be > 0 ms");
  if (!opt.html.empty()) web_asset("chart_page.js");  // a build without the web report fails before measuring
  const Device device = select_device(device_spec_from(opt.device));
  std::cout << "device " << describe_device(device.info) << "\n";
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(device);
  PairOptions pair_options;
  pair_options.descriptors.progress = pass_progress_bars();
  const AssemblyPair pair = build_assembly_pair(scene, ctx, fft, pair_options);
  const QueryVariant variant = query_variant_for(scene, parse_interpolation(opt.interpolation));
  auto engine = make_query_engine(ctx, pair.spectra, variant);
  std::cout << "variant " << variant_name(variant) << ", " << engine->max_modes() << " modes available, budget "
            << budget << " ms, margin " << opt.margin * 100 << " %\n";

  const std::vector<Pose> poses = tuning_poses(scene);
  TuneOptions tune;
  tune.repetitions = opt.repetitions;
  const auto bars = pass_progress_bars();  // one bar, finished when the sweep ends
  tune.progress = [bars](std::uint64_t done, std::uint64_t total) { bars("tuning m'", done, total); };
  const TuningKey key = tuning_key_for(device.info, variant, pair.spectra, budget, opt.margin, scene.loop_rate_hz);
  const EngineTuning tuned =
      tune_engine(*engine, key, poses, tune, true, [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; });
  std::cout << tuning_table(tuned.result) << "saved to " << tuned.path << "\n";
  if (!opt.html.empty()) {
    write_chart_page(opt.html, "snapfit tune: " + scene.name,
                     {"Scene " + scene.source_path + ", device " + device.info.name + ", " + variant_name(variant) +
                      ", measured " + tuned.result.created},
                     {tuning_chart(tuned.result, device.info.name)});
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
