// `snapfit run SCENE`: the main job. Today it loads the scene, builds and validates
// both parts in parallel, opens the OpenCL device, builds (or loads from the program
// cache) and self-checks the kernels, prints the compute plan, and writes a report
// folder with the part meshes and a JSON summary. Later stages (descriptors, spectra,
// the haptic loop) add their steps here.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/scene_summary.h"
#include "engine/device_check.h"
#include "engine/error.h"
#include "io/mesh_export.h"
#include "io/mesh_report.h"

namespace snapfit::cli {
namespace {

struct RunOptions {
  std::string scene;
  std::string device;
  std::string out;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void run_main_job(const RunOptions& opt) {
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  std::cout << "[1/4] reading scene " << opt.scene << "\n";
  const Scene scene = load_scene(opt.scene);

  std::cout << "[2/4] building and validating both parts (in parallel)\n";
  const PreparedParts parts = prepare_parts(scene);
  const ComputePlan plan = plan_computation(scene);
  print_scene_summary(std::cout, scene, parts, plan);

  std::cout << "[3/4] opening the OpenCL device and checking it\n";
  const Device device = select_device(device_spec_from(opt.device));
  std::cout << "    device " << describe_device(device.info) << "\n";
  const ComputeContext ctx = make_compute_context(device);
  const DeviceCheckResult check = run_device_check(ctx, false);
  std::cout << "    self-check " << (check.passed ? "passed" : "FAILED") << " (relative error " << check.relative_error
            << ", program " << (check.origin == ProgramOrigin::cache_hit ? "from cache" : "compiled") << " in "
            << check.build_ms << " ms)\n";
  if (!check.passed) throw Error("device " + device.info.name + " failed its self-check; choose another with --device");

  const fs::path out = opt.out.empty() ? fs::path("results") / fs::path(opt.scene).stem() : fs::path(opt.out);
  std::cout << "[4/4] writing the report to " << out.string() << "\n";
  fs::create_directories(out);
  write_stl(parts.part1.mesh, (out / "part1.stl").string());
  write_stl(parts.part2.mesh, (out / "part2.stl").string());
  nlohmann::json summary = {
      {"scene", scene.name},
      {"scene_file", scene.source_path},
      {"units", scene.units},
      {"device", device.info.name},
      {"driver", device.info.driver_version},
      {"device_check_passed", check.passed},
      {"part1", nlohmann::json::parse(mesh_report_json(parts.part1.report))},
      {"part2", nlohmann::json::parse(mesh_report_json(parts.part2.report))},
      {"plan", plan.lines},
      {"seconds", seconds_since(start)},
  };
  std::ofstream(out / "summary.json") << summary.dump(2) << "\n";
  std::cout << "done in " << seconds_since(start) << " s: " << (out / "summary.json").string() << ", part1.stl, part2.stl\n";
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "The main job: prepare a scene's parts and device, write a report folder");
  cmd->add_option("scene", opt->scene, "Scene file (JSON, see scenes/README.md)")->required();
  cmd->add_option("--device", opt->device, "OpenCL device: index, platform:device, cpu|gpu|accelerator, or a name substring (default: $SNAPFIT_DEVICE, else PoCL's CPU device)");
  cmd->add_option("--out", opt->out, "Report folder (default: results/<scene name>)");
  cmd->callback([opt] { run_main_job(*opt); });
}

}  // namespace snapfit::cli
