// `snapfit run SCENE`: the main job. Loads the scene, builds and validates both parts in
// parallel, opens the OpenCL device and self-checks it, prints the compute plan,
// computes (or loads from the caches) both parts' descriptor fields and their spectra,
// tunes m' for the frame budget on this device and the others (or loads the tuning
// files), plays the scene's scripted trajectory through the 1 kHz haptic loop in real
// time (all of it snapfit::run_job, snapfit/job.h), and writes the report folder
// (report/run_report.h).
#include <chrono>
#include <filesystem>
#include <iostream>
#include <optional>

#include "cli/cli_terms.h"
#include "cli/commands.h"
#include "cli/parse_options.h"
#include "report/run_report.h"
#include "snapfit/job.h"

namespace snapfit::cli {
namespace {

struct RunOptions {
  std::string scene;
  std::string device;
  std::string out;
  std::optional<std::size_t> modes;  // fixed m' instead of the tuned one
  double margin = 0.25;
  bool retune = false;
  bool simulated_time = false;
  std::string loop_wait = "spin";
  std::string strategy = "auto";  // auto | tricubic | trilinear | exact-product | near-far
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::filesystem::path report_folder(const RunOptions& opt) {
  return opt.out.empty() ? std::filesystem::path("results") / std::filesystem::path(opt.scene).stem()
                         : std::filesystem::path(opt.out);
}

// Writes the report folder and says where it went.
void write_report(const RunOptions& opt, JobResult& result, std::chrono::steady_clock::time_point start) {
  const std::filesystem::path out = report_folder(opt);
  std::cout << "writing the report to " << out.string() << "\n";
  const RunReportFiles report = write_job_report(out, result, seconds_since(start));
  std::cout << "done in " << seconds_since(start) << " s: " << (out / report.written.front()).string();
  for (std::size_t i = 1; i < report.written.size(); ++i) std::cout << ", " << report.written[i];
  std::cout << "\n";
  for (const std::string& warning : report.warnings) std::cerr << "snapfit: " << warning << "\n";
}

void run_main_job(const RunOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  std::cout << "[1/7] reading scene " << opt.scene << "\n";
  const Scene scene = load_scene(opt.scene);
  check_output_folder(report_folder(opt).string());  // before the work, not after it
  JobRequest request;
  request.device = opt.device;
  request.modes = opt.modes.value_or(0);
  request.margin = opt.margin;
  request.retune = opt.retune;
  request.strategy = opt.strategy;
  request.simulated_time = opt.simulated_time;
  request.loop_wait = parse_loop_wait(opt.loop_wait);
  request.progress = true;
  request.say = [](const std::string& text) { std::cout << in_cli_terms(text) << std::flush; };
  request.note = [](const std::string& text) { std::cerr << "snapfit: " << in_cli_terms(text) << "\n"; };
  JobResult result = run_job(scene, request);
  write_report(opt, result, start);
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "The main job: prepare a scene's parts and device, write a report folder");
  cmd->add_option("scene", opt->scene, "Scene file (JSON, see docs/scenes.md)")->required();
  cmd->add_option("--device", opt->device,
                  "OpenCL device: index, platform:device, cpu|gpu|accelerator, or a name substring (default: "
                  "$SNAPFIT_DEVICE, else PoCL's CPU device)");
  cmd->add_option("--out", opt->out, "Report folder (default: results/<scene name>)");
  cmd->add_option("--modes", opt->modes, "m': a fixed number of Fourier modes instead of the tuned one")
      ->check(positive_number());
  cmd->add_option("--margin", opt->margin, "Tuning safety margin: p99 at most (1 - margin) of the frame budget")
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_flag("--retune", opt->retune,
                "Measure m' and the strategies' errors again even when the tuning and strategy files match");
  cmd->add_option("--strategy", opt->strategy,
                  "Query strategy: auto (default: the lowest error that fits the frame, measured once per scene and "
                  "device against the exact reference, after the first run's loop, which starts on tricubic; "
                  "tricubic with --modes), tricubic, trilinear, exact-product or near-far")
      ->check(CLI::IsMember(strategy_choices()));
  cmd->add_flag("--simulated-time", opt->simulated_time,
                "Run the loop on simulated time: deterministic, as fast as the queries go, no timing meaning");
  cmd->add_option("--loop-wait", opt->loop_wait,
                  "How the loop waits for its tick: spin (default; keeps a core awake, fewest late frames on a "
                  "virtual machine) or sleep (frees the core between frames; SCHED_FIFO where allowed)")
      ->check(CLI::IsMember({"spin", "sleep"}));
  cmd->callback([opt] { run_main_job(*opt); });
}

}  // namespace snapfit::cli
