// `snapfit run SCENE`: the main job. Loads the scene, builds and validates both parts in
// parallel, opens the OpenCL device and self-checks it, prints the compute plan,
// computes (or loads from the caches) both parts' descriptor fields and their spectra,
// tunes m' for the frame budget on this device (or loads the tuning file), plays the
// scene's scripted trajectory through the 1 kHz haptic loop in real time, and writes
// a report folder: part meshes, affinity slices, the tuning sweep, the loop's per-frame
// log and charts, and summary.json with frame-time statistics, m' changes and the
// final pose error against the assembled pose.
#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "report/haptic_report.h"
#include "scheduler/assembly_session.h"
#include "scheduler/device_choice.h"
#include "scheduler/engine_tuning.h"
#include "core/quantile.h"
#include "report/scene_summary.h"
#include "engine/device_check.h"
#include "snapfit/error.h"
#include "pipeline/assembly_pair.h"
#include "engine/query_engine.h"
#include "pipeline/part_fields.h"
#include "report/plot.h"
#include "pipeline/spectra_cache.h"
#include "scheduler/trajectory.h"
#include "io/png_export.h"
#include "core/progress.h"
#include "io/mesh_export.h"
#include "io/atomic_write.h"
#include "mesh/mesh_report.h"

namespace snapfit::cli {
namespace {

struct RunOptions {
  std::string scene;
  std::string device;
  std::string out;
  std::optional<std::size_t> modes;  // fixed m' instead of the tuned one
  double margin = 0.25;
  bool retune = false;
};

// Poses the tuner times queries at: the scene's trajectory at 100 Hz, else part 2's pose.
std::vector<Pose> tuning_poses(const Scene& scene) {
  if (scene.trajectory.keyframes.empty()) return {scene.part2.pose};
  return sample_trajectory(scene.trajectory, 100.0);
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void run_main_job(const RunOptions& opt) {
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  std::cout << "[1/7] reading scene " << opt.scene << "\n";
  const Scene scene = load_scene(opt.scene);

  std::cout << "[2/7] building and validating both parts (in parallel)\n";
  const PreparedParts parts = prepare_parts(scene);
  const ComputePlan plan = plan_computation(scene);
  print_scene_summary(std::cout, scene, parts, plan);

  std::cout << "[3/7] opening the OpenCL device and checking it\n";
  const Device device = select_device(device_spec_from(opt.device));
  std::cout << "    device " << describe_device(device.info) << "\n";
  const ComputeContext ctx = make_compute_context(device);
  const DeviceCheckResult check = run_device_check(ctx, false);
  std::cout << "    self-check " << (check.passed ? "passed" : "FAILED") << " (relative error " << check.relative_error
            << ", program " << (check.origin == ProgramOrigin::cache_hit ? "from cache" : "compiled") << " in "
            << check.build_ms << " ms)\n";
  if (!check.passed) throw Error("device " + device.info.name + " failed its self-check; choose another with --device");

  const ScenePartGrids grids = scene_part_grids(scene.grid, parts.part1.mesh, parts.part2.mesh);
  std::cout << "[4/7] descriptor fields of both parts at spacing " << grids.spacing << " " << scene.units
            << " (from the field cache when present)\n";
  DescriptorOptions options;
  options.progress = pass_progress_bars();
  const auto note = [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  std::vector<PartFieldsResult> fields;
  for (int part = 1; part <= 2; ++part) {
    const Mesh& mesh = part == 1 ? parts.part1.mesh : parts.part2.mesh;
    const GridSpec& grid = part == 1 ? grids.part1 : grids.part2;
    std::cout << "  part " << part << ": grid " << grid.dims.x() << " x " << grid.dims.y() << " x " << grid.dims.z()
              << " = " << grid.count() << " points, " << mesh.triangles.size() << " triangles" << std::endl;
    fields.push_back(part_fields(ctx, mesh, grid, scene.descriptor, options, true, note));
    print_fields_summary(std::cout, fields.back());
  }

  // Spectra (cached) and the query engine.
  const bool torque = plan.torque_fields;
  std::cout << "[5/7] spectra (from the spectra cache when present) and the query engine\n";
  const FftLibrary fft;
  const SpectrumOptions spectrum_options;
  const std::string spectra_key = spectra_cache_key(fields[0].fields, fields[1].fields, torque, spectrum_options);
  std::optional<PairSpectra> spectra = load_cached_spectra(spectra_key, note);
  if (!spectra) {
    spectra = compute_pair_spectra(fft, ctx, fields[0].fields, fields[1].fields, torque, spectrum_options);
    save_cached_spectra(spectra_key, *spectra, note);
  }
  const QueryVariant variant = query_variant_for(scene, Interpolation::tricubic);
  auto engine = make_query_engine(ctx, *spectra, variant);
  std::cout << "    FFT grid " << spectra->dims[0] << " x " << spectra->dims[1] << " x " << spectra->dims[2] << ", "
            << engine->max_modes() << " modes, kernel variant: " << variant_name(variant) << "\n";

  // m' for this device: the tuning file, else a measured sweep (scheduler/auto_tune.h).
  std::cout << "[6/7] m' for a " << scene.frame_budget_ms << " ms frame on this device\n";
  TuningKey key = tuning_key_for(device.info, variant, *spectra, scene.frame_budget_ms, opt.margin, scene.loop_rate_hz);
  TuningResult tuning;
  QueryEngine* loop_engine = engine.get();
  // Other devices, when the user did not pick one: the loop goes to the lowest tuned latency.
  std::vector<std::unique_ptr<ComputeContext>> other_contexts;
  std::vector<std::unique_ptr<QueryEngine>> other_engines;
  if (opt.modes) {
    tuning = pick_modes({TimingPoint{std::min(*opt.modes, engine->max_modes()), 0, 0, 0, 0}}, scene.frame_budget_ms,
                        opt.margin);
    std::cout << "    m' = " << tuning.chosen_modes << " (--modes; not tuned)\n";
  } else {
    const std::vector<Pose> poses = tuning_poses(scene);
    const auto tune_on = [&](QueryEngine& e, const TuningKey& k) {
      TuneOptions tune_options;
      const auto bars = pass_progress_bars();  // one bar, finished when the sweep ends
      tune_options.progress = [bars](std::uint64_t done, std::uint64_t total) { bars("    tuning m'", done, total); };
      const EngineTuning tuned = tune_engine(e, k, poses, tune_options, opt.retune, note);
      std::cout << "    " << (tuned.from_file ? "from the tuning file " : "measured and saved to ") << tuned.path
                << "\n" << tuning_table(tuned.result);
      return tuned.result;
    };
    std::vector<TuningResult> tunings{tune_on(*engine, key)};
    std::vector<TuningKey> keys{key};
    std::vector<std::string> names{device.info.name};
    std::vector<bool> in_caller_thread{device.info.runs_in_caller_thread()};
    if (device_spec_from(opt.device).empty())
      for (const Device& other : enumerate_devices()) {
        if (other.info.index == device.info.index) continue;
        try {
          auto other_ctx = std::make_unique<ComputeContext>(make_compute_context(other));
          if (!run_device_check(*other_ctx, false).passed) continue;
          std::cout << "    also tuning " << describe_device(other.info) << "\n";
          auto other_engine = make_query_engine(*other_ctx, *spectra, variant);
          keys.push_back(tuning_key_for(other.info, variant, *spectra, scene.frame_budget_ms, opt.margin, scene.loop_rate_hz));
          tunings.push_back(tune_on(*other_engine, keys.back()));
          names.push_back(other.info.name);
          in_caller_thread.push_back(other.info.runs_in_caller_thread());
          other_contexts.push_back(std::move(other_ctx));
          other_engines.push_back(std::move(other_engine));
        } catch (const Error& e) {
          note("device " + other.info.name + " left out of the loop choice: " + e.what());
        }
      }
    const std::size_t pick = loop_device(tunings, in_caller_thread);
    if (tunings.size() > 1)
      std::cout << "    the loop runs on " << names[pick] << " (of " << tunings.size() << " tuned devices: "
                << (in_caller_thread[pick] ? "runs kernels in the loop's own thread, "
                                           : "")
                << "m' " << tunings[pick].chosen_modes << ", scheduler/device_choice.h)\n";
    if (pick > 0) loop_engine = other_engines[pick - 1].get();
    tuning = tunings[pick];
    key = keys[pick];
  }

  // The scripted assembly through the haptic loop, in real time.
  nlohmann::json loop_summary = nullptr;
  std::optional<SessionResult> session;
  if (!scene.trajectory.keyframes.empty()) {
    const Trajectory& t = scene.trajectory;
    const double seconds = t.keyframes.back().time_s - t.keyframes.front().time_s + scene.haptics.settle_s;
    std::cout << "[7/7] haptic loop at " << scene.loop_rate_hz << " Hz playing the scripted trajectory ("
              << seconds << " s of real time, m' = " << tuning.chosen_modes << ")\n";
    session = run_scripted_assembly(scene, parts.part2.mesh, spectra->spacing, *loop_engine, tuning);
    const LoopReport& loop = session->loop;
    if (session->priority.failed)
      note("could not raise the priority of " + std::to_string(session->priority.failed) +
           " threads for the loop (" + session->priority.reason + "); frames may be late on a busy machine");
    std::cout << "    " << loop.frames << " frames, measured " << loop.measured_rate_hz << " Hz; frame time p50 "
              << quantile(loop.frame_ms, 0.5) << " ms, p99 " << quantile(loop.frame_ms, 0.99) << " ms, max "
              << quantile(loop.frame_ms, 1.0) << " ms; " << loop.misses << " misses (" << 100 * loop.miss_rate()
              << " %; " << loop.late_wakeup_misses << " late wake-ups, " << loop.stall_misses << " stalls), "
              << loop.mode_changes.size() << " m' changes; threads: " << session->priority.describe() << "\n";
    for (const ModeChange& c : loop.mode_changes)
      std::cout << "      t = " << c.time_s << " s: m' " << c.from << " -> " << c.to << " (" << c.reason << ")\n";
    std::cout << "    final pose error " << session->final_error.position << " " << scene.units << ", "
              << session->final_error.angle_deg << " deg (tolerance " << session->position_tolerance << " "
              << scene.units << ", " << session->angle_tolerance_deg << " deg): "
              << (session->assembled ? "ASSEMBLED" : "NOT assembled") << "\n";
  } else {
    std::cout << "[7/7] the scene has no trajectory: no scripted assembly to run\n";
  }

  const fs::path out = opt.out.empty() ? fs::path("results") / fs::path(opt.scene).stem() : fs::path(opt.out);
  std::cout << "writing the report to " << out.string() << "\n";
  fs::create_directories(out);
  write_stl(parts.part1.mesh, (out / "part1.stl").string());
  write_stl(parts.part2.mesh, (out / "part2.stl").string());
  // A slice of each part's affinity through y = 0 of its own frame (seed 000 Fig. 2 style).
  nlohmann::json field_summary = nlohmann::json::array();
  for (int part = 1; part <= 2; ++part) {
    const DescriptorFields& f = fields[part - 1].fields;
    const std::vector<float> rho = affinity_imaginary(f);
    const int slice = slice_index_for(f.grid, 'y', std::clamp(0.0, f.grid.origin.y(), f.grid.point(0, f.grid.dims.y() - 1, 0).y()));
    const ColorMap map = f.skeletal_density.empty() ? ColorMap::sequential : ColorMap::diverging;
    const std::string png = "part" + std::to_string(part) + "_affinity_y0.png";
    write_png((out / png).string(), render_slice(f.grid, rho.data(), 'y', slice, map, std::nullopt, 4),
              {{"Title", "snapfit affinity Im(rho) of part " + std::to_string(part) + " at y=0"}});
    double max_bound = 0;
    for (float b : f.density_bound) max_bound = std::max(max_bound, static_cast<double>(b));
    field_summary.push_back({{"part", part},
                             {"grid_points", f.grid.count()},
                             {"dims", {f.grid.dims.x(), f.grid.dims.y(), f.grid.dims.z()}},
                             {"from_cache", fields[part - 1].from_cache},
                             {"seconds", f.seconds},
                             {"max_density_bound", max_bound},
                             {"affinity_png", png}});
  }
  nlohmann::json tuning_summary = nlohmann::json::parse(tuning_to_json(tuning));
  tuning_summary["key"] = key.text();
  if (session) loop_summary = write_haptic_report(out, scene, *session, tuning);
  else write_chart_png((out / "tuning.png").string(), tuning_chart(tuning, device.info.name));

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
      {"spacing", grids.spacing},
      {"fields", field_summary},
      {"tuning", tuning_summary},
      {"haptic_loop", loop_summary},
      {"seconds", seconds_since(start)},
  };
  std::ofstream(out / "summary.json") << summary.dump(2) << "\n";
  std::cout << "done in " << seconds_since(start) << " s: " << (out / "summary.json").string()
            << ", part1.stl, part2.stl, part1_affinity_y0.png, part2_affinity_y0.png, tuning.png"
            << (session ? ", loop.csv, frame_times.png, energy.png, force_torque.png, pose_error.png" : "") << "\n";
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "The main job: prepare a scene's parts and device, write a report folder");
  cmd->add_option("scene", opt->scene, "Scene file (JSON, see scenes/README.md)")->required();
  cmd->add_option("--device", opt->device, "OpenCL device: index, platform:device, cpu|gpu|accelerator, or a name substring (default: $SNAPFIT_DEVICE, else PoCL's CPU device)");
  cmd->add_option("--out", opt->out, "Report folder (default: results/<scene name>)");
  cmd->add_option("--modes", opt->modes, "m': a fixed number of Fourier modes instead of the tuned one");
  cmd->add_option("--margin", opt->margin, "Tuning safety margin: p99 at most (1 - margin) of the frame budget")
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_flag("--retune", opt->retune, "Measure m' again even when the tuning file matches");
  cmd->callback([opt] { run_main_job(*opt); });
}

}  // namespace snapfit::cli
