// `snapfit run SCENE`: the main job. Loads the scene, builds and validates both parts in
// parallel, opens the OpenCL device and self-checks it, prints the compute plan,
// computes (or loads from the caches) both parts' descriptor fields and their spectra
// (the pipeline, pipeline/assembly_pair.h), tunes m' for the frame budget on this device
// and the others (scheduler/loop_devices.h; or loads the tuning files), plays the scene's
// scripted trajectory through the 1 kHz haptic loop in real time, and writes the report
// folder (report/run_report.h).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <optional>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "core/progress.h"
#include "core/quantile.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device_check.h"
#include "mesh/procedural/procedural_parts.h"
#include "pipeline/assembly_pair.h"
#include "report/haptic_report.h"
#include "report/run_report.h"
#include "report/scene_summary.h"
#include "report/slice_figure.h"
#include "report/web_assets.h"
#include "scheduler/assembly_session.h"
#include "scheduler/loop_devices.h"
#include "scheduler/query_strategy.h"
#include "scheduler/vps/vps_hybrid.h"
#include "scheduler/vps/vps_method.h"
#include "snapfit/error.h"

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
  std::string strategy = "auto";  // auto | tricubic | trilinear | exact-product
};

// The variant --strategy names for `scene` (auto: the scene's tricubic variant, the
// starting point of the measured choice).
QueryVariant named_strategy(const Scene& scene, const std::string& name) {
  QueryVariant v = query_variant_for(scene, Interpolation::tricubic);
  if (v.translation_only) {
    if (name != "auto" && name != "tricubic")
      throw Error("--strategy " + name + ": a translation-only scene has one strategy, the translation lines");
    return v;
  }
  if (name == "trilinear") v.interpolation = Interpolation::trilinear;
  if (name == "exact-product") {
    v.rotation = RotationMethod::exact_product;
    v.product_update = ProductUpdate::background;
  }
  return v;
}

void print_strategies(const StrategyChoice& choice) {
  std::cout << "    " << (choice.from_file ? "from the strategy file " : "measured and saved to ") << choice.path
            << "\n    strategy                                                m'   p99 ms   energy    force   torque\n"
            << std::flush;
  for (std::size_t i = 0; i < choice.report.strategies.size(); ++i) {
    const StrategyAccuracy& s = choice.report.strategies[i];
    std::printf("    %-50s %9zu %8.3f %7.2f%% %7.2f%% %7.2f%%%s%s\n", s.name.c_str(), s.modes, s.frame_ms_p99,
                100 * s.energy_error, 100 * s.force_error, 100 * s.torque_error, s.fits ? "" : "  does not fit",
                i == choice.report.best ? "  <- chosen" : "");
  }
  std::cout << std::flush << "    " << choice.report.why << "\n";
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void print_loop(const Scene& scene, const SessionResult& session) {
  const LoopReport& loop = session.loop;
  if (!session.contact_off.empty()) std::cerr << "snapfit: " << session.contact_off << "\n";
  if (session.contact)
    std::cout << "    rigid contact: built in " << session.contact_build_s << " s, " << session.contact_ms
              << " ms a frame (p99 near the fit) left out of the query's budget: the loop starts at m' "
              << session.start_modes << "\n";
  std::cout << "    " << loop.frames << " frames, measured " << loop.measured_rate_hz << " Hz; frame time p50 "
            << quantile(loop.frame_ms, 0.5) << " ms, p99 " << quantile(loop.frame_ms, 0.99) << " ms, max "
            << quantile(loop.frame_ms, 1.0) << " ms; " << loop.misses << " misses (" << 100 * loop.miss_rate() << " %; "
            << loop.late_wakeup_misses << " late wake-ups, " << loop.stall_misses << " stalls), "
            << loop.mode_changes.size() << " m' changes; threads: " << session.priority.describe() << "\n";
  for (const ModeChange& c : loop.mode_changes)
    std::cout << "      t = " << c.time_s << " s: m' " << c.from << " -> " << c.to << " (" << c.reason << ")\n";
  std::cout << "    final pose error " << session.final_error.position << " " << scene.units << ", "
            << session.final_error.angle_deg << " deg (tolerance " << session.position_tolerance << " " << scene.units
            << ", " << session.angle_tolerance_deg << " deg): "
            << (!session.evaluated  ? "not evaluated (the scene has no assembled pose)"
                : session.assembled ? "ASSEMBLED"
                                    : "NOT assembled")
            << "\n      " << final_error_text(session, scene.units) << "\n";
}

// Writes the report folder and says where it went.
std::filesystem::path report_folder(const RunOptions& opt) {
  return opt.out.empty() ? std::filesystem::path("results") / std::filesystem::path(opt.scene).stem()
                         : std::filesystem::path(opt.out);
}

void write_report(const RunOptions& opt, RunRecord& record, std::chrono::steady_clock::time_point start) {
  namespace fs = std::filesystem;
  const fs::path out = report_folder(opt);
  std::cout << "writing the report to " << out.string() << "\n";
  record.seconds = seconds_since(start);
  const std::vector<std::string> written = write_run_report(out, record);
  std::cout << "done in " << seconds_since(start) << " s: " << (out / written.front()).string();
  for (std::size_t i = 1; i < written.size(); ++i) std::cout << ", " << written[i];
  std::cout << "\n";
  if (!web_pages_available())
    std::cerr << "snapfit: no report.html: this snapfit was built with -DSNAPFIT_WEB_REPORT=OFF (no node/npm at build "
                 "time)\n";
  if (const std::string font = figure_font_problem(); !font.empty() && !record.vps)
    std::cerr << "snapfit: " << font << ": the field figures' labels are not readable\n";
}

// A scene with "method": "vps": part 1's voxmap and part 2's point shell on the host,
// then the same scripted loop and report (no device, fields, spectra or tuning).
void run_vps_job(const RunOptions& opt, const AssemblyPair& pair, std::chrono::steady_clock::time_point start) {
  const Scene& scene = pair.scene;
  std::cout << "[3/7] Voxmap PointShell: voxelising part 1, point shell of part 2 (no OpenCL device)\n";
  const auto built = std::chrono::steady_clock::now();
  const CouplingParams coupling = coupling_for(scene, pair.part(2).mesh);
  const VpsModel model = vps_model_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing, coupling);
  RunRecord record;
  record.pair = &pair;
  VpsFacts& facts = record.vps.emplace();
  facts.voxel_size = model.voxmap.voxel_size;
  facts.shell_spacing = model.shell.spacing;
  facts.surface_voxels = model.voxmap.count(VoxelState::surface);
  facts.interior_voxels = model.voxmap.count(VoxelState::interior);
  facts.proximity_voxels = model.voxmap.count(VoxelState::proximity);
  facts.shell_points = model.shell.points.size();
  facts.stiffness_n_per_m = model.stiffness;
  facts.braking_n_s_per_m = model.braking;
  facts.build_seconds = seconds_since(built);
  record.device.name = record.loop_device.name = "host";
  std::cout << "    voxel " << facts.voxel_size << " " << scene.units << ": " << facts.surface_voxels << " surface, "
            << facts.interior_voxels << " interior, " << facts.proximity_voxels << " proximity voxels; "
            << facts.shell_points << " shell points at " << facts.shell_spacing << " " << scene.units << " (built in "
            << facts.build_seconds << " s)\n";
  // The hybrid needs both parts' analytic faces; a part without them runs as plain VPS.
  std::optional<HybridModel> hybrid;
  std::optional<HybridState> hybrid_state;
  if (scene.method == Method::vps_hybrid) {
    std::vector<AnalyticFace> f1 = pair.part(1).faces, f2 = pair.part(2).faces;
    for (const PartSpec* p : {&scene.part1, &scene.part2})
      if ((p == &scene.part1 ? f1 : f2).empty())
        facts.plain_reason += std::string(facts.plain_reason.empty() ? "" : "; ") + "part '" + p->name + "' " +
                              (p->procedural ? "(procedural " + p->procedural->type + ")"
                               : (p == &scene.part1 ? pair.part(1) : pair.part(2)).cad
                                   ? std::string("(a CAD file with no plane, cylinder or cone)")
                                   : std::string("(a mesh file)")) +
                              " has no analytic faces";
    if (!facts.plain_reason.empty()) {
      std::cout << "    vps_hybrid: " << facts.plain_reason << ": running as plain Voxmap PointShell\n";
    } else {
      facts.faces1 = f1.size();
      facts.faces2 = f2.size();
      hybrid = hybrid_model(model, std::move(f1), std::move(f2), coupling, hybrid_params_for(scene));
      hybrid_state = hybrid_state_for(*hybrid);
      facts.hybrid = true;
      facts.labelled_voxels =
          std::count_if(hybrid->voxel_face.begin(), hybrid->voxel_face.end(), [](std::int16_t f) { return f >= 0; });
      facts.labelled_points =
          std::count_if(hybrid->point_face.begin(), hybrid->point_face.end(), [](std::int16_t f) { return f >= 0; });
      facts.alignment_k_n_per_m = hybrid->k_a_n_per_m;
      std::cout << "    vps_hybrid: " << facts.faces1 << " + " << facts.faces2 << " analytic faces; "
                << facts.labelled_voxels << " surface voxels and " << facts.labelled_points
                << " shell points on one face; alignment k_A " << facts.alignment_k_n_per_m << " N/m\n";
    }
  }
  if (!scene.trajectory.keyframes.empty()) {
    const Trajectory& t = scene.trajectory;
    const double seconds = t.keyframes.back().time_s - t.keyframes.front().time_s + scene.haptics.settle_s;
    std::cout << "[7/7] haptic loop at " << scene.loop_rate_hz << " Hz playing the scripted trajectory (" << seconds
              << " s of " << (opt.simulated_time ? "simulated" : "real") << " time, "
              << (hybrid ? "VPS - constraint hybrid" : "Voxmap PointShell") << ")\n";
    SessionOptions session;
    session.simulated_time = opt.simulated_time;
    session.wait = parse_loop_wait(opt.loop_wait);
    record.session =
        run_scripted_session(scene, pair.grids.spacing, vps_loop_config(scene, model, coupling),
                             hybrid ? hybrid_evaluator(*hybrid, *hybrid_state) : vps_evaluator(model), session);
    print_loop(scene, *record.session);
  } else {
    std::cout << "[7/7] the scene has no trajectory: no scripted assembly to run\n";
  }
  write_report(opt, record, start);
}

void run_main_job(const RunOptions& opt) {
  const auto start = std::chrono::steady_clock::now();
  const auto note = [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  std::cout << "[1/7] reading scene " << opt.scene << "\n";
  const Scene scene = load_scene(opt.scene);
  check_output_folder(report_folder(opt).string());  // before the work, not after it

  std::cout << "[2/7] building and validating both parts (in parallel)\n";
  AssemblyPair pair = prepare_assembly_pair(scene);
  print_scene_summary(std::cout, scene, pair.parts, pair.plan);
  if (uses_vps(scene.method)) return run_vps_job(opt, pair, start);

  std::cout << "[3/7] opening the OpenCL device and checking it\n";
  const Device device = select_device(device_spec_from(opt.device));
  std::cout << "    device " << describe_device(device.info) << "\n";
  const ComputeContext ctx = make_compute_context(device);
  const DeviceCheckResult check = run_device_check(ctx, false);
  std::cout << "    self-check " << (check.passed ? "passed" : "FAILED") << " (relative error " << check.relative_error
            << ", program " << (check.origin == ProgramOrigin::cache_hit ? "from cache" : "compiled") << " in "
            << check.build_ms << " ms)\n";
  if (!check.passed) throw Error("device " + device.info.name + " failed its self-check; choose another with --device");

  std::cout << "[4/7] descriptor fields of both parts at spacing " << pair.grids.spacing << " " << scene.units
            << " (from the field cache when present)\n";
  PairOptions pair_options;
  pair_options.descriptors.progress = pass_progress_bars();
  pair_options.note = note;
  for (int part = 1; part <= 2; ++part) {
    const GridSpec& grid = pair.grid(part);
    std::cout << "  part " << part << ": grid " << grid.dims.x() << " x " << grid.dims.y() << " x " << grid.dims.z()
              << " = " << grid.count() << " points, " << pair.part(part).mesh.triangles.size() << " triangles"
              << std::endl;
    compute_assembly_fields(pair, ctx, pair_options, part);
    print_fields_summary(std::cout, pair.fields(part));
  }

  std::cout << "[5/7] spectra (from the spectra cache when present) and the query engine\n";
  const FftLibrary fft;
  compute_assembly_spectra(pair, ctx, fft, pair_options);
  const QueryVariant variant = named_strategy(scene, opt.strategy);
  const auto& dims = pair.spectra.dims;
  std::cout << "    FFT grid " << dims[0] << " x " << dims[1] << " x " << dims[2]
            << (pair.spectra_from_cache ? " (cached)" : "") << ", query variant tuned first: " << variant_name(variant)
            << "\n";

  // m' for this device: the tuning file, else a measured sweep; with several devices the
  // loop goes to the one scheduler/device_choice.h picks.
  std::cout << "[6/7] the query strategy and m' for a " << scene.frame_budget_ms << " ms frame on this device\n";
  RunRecord record;
  record.pair = &pair;
  record.device = device.info;
  record.check = check;
  std::optional<LoopDevices> devices;
  std::unique_ptr<QueryEngine> fixed_engine;
  QueryEngine* loop_engine = nullptr;
  if (opt.modes) {
    fixed_engine = make_query_engine(ctx, pair.spectra, variant);
    record.tuning = pick_modes({TimingPoint{std::min(*opt.modes, fixed_engine->max_modes()), 0, 0, 0, 0}},
                               scene.frame_budget_ms, opt.margin);
    record.loop_device = device.info;
    loop_engine = fixed_engine.get();
    record.strategy = variant_name(variant);
    record.strategy_chosen_by = opt.strategy == "auto" ? "--modes (not measured)" : "--strategy";
    std::cout << "    " << record.strategy << ", m' = " << record.tuning.chosen_modes << " (--modes; not tuned)\n";
  } else {
    LoopDeviceOptions tune;
    tune.margin = opt.margin;
    tune.retune = opt.retune;
    tune.other_devices = device_spec_from(opt.device).empty();
    tune.note = note;
    const auto bars = pass_progress_bars();  // one bar per sweep, finished when it ends
    tune.tune.progress = [bars](std::uint64_t done, std::uint64_t total) { bars("    tuning m'", done, total); };
    tune.on_start = [&](const DeviceInfo& info) {
      if (info.index != device.info.index) std::cout << "    also tuning " << describe_device(info) << "\n";
    };
    tune.on_tuned = [](const TunedDevice& d) {
      std::cout << "    " << (d.tuning.from_file ? "from the tuning file " : "measured and saved to ") << d.tuning.path
                << "\n"
                << tuning_table(d.tuning.result);
    };
    devices = tune_loop_devices(ctx, scene, pair.spectra, variant, tune);
    record.strategy_chosen_by = "--strategy";
    if (opt.strategy == "auto") {
      // Every strategy the scene allows, measured against the exact reference on the
      // loop's device (once; then the strategy file), and the most accurate that fits.
      AccuracyOptions accuracy;
      accuracy.budget_ms = scene.frame_budget_ms;
      accuracy.margin = opt.margin;
      accuracy.retune = opt.retune;
      accuracy.note = note;
      accuracy.progress = pass_progress_bars();
      const StrategyChoice choice = choose_query_strategy(devices->loop().ctx, scene, pair.spectra, accuracy);
      print_strategies(choice);
      record.strategies = choice.report;
      record.strategy_file = choice.path;
      record.strategy_chosen_by =
          std::string("lowest error that fits (") + (choice.from_file ? "strategy file" : "measured") + ")";
      if (variant_name(choice.chosen().variant) != variant_name(variant))
        use_variant_on_loop_device(*devices, scene, pair.spectra, choice.chosen().variant, tune);
    }
    const TunedDevice& chosen = devices->loop();
    record.strategy = variant_name(chosen.engine->variant());
    if (devices->devices.size() > 1)
      std::cout << "    the loop runs on " << chosen.ctx.device.info.name << " (of " << devices->devices.size()
                << " tuned devices: "
                << (chosen.ctx.device.info.runs_in_caller_thread() ? "runs kernels in the loop's own thread, " : "")
                << "m' " << chosen.tuning.result.chosen_modes << ", scheduler/device_choice.h)\n";
    record.tuning = chosen.tuning.result;
    record.tuning_key = chosen.key.text();
    record.loop_device = chosen.ctx.device.info;
    loop_engine = chosen.engine.get();
  }

  // The scripted assembly through the haptic loop, in real time (or simulated time).
  if (!scene.trajectory.keyframes.empty()) {
    const Trajectory& t = scene.trajectory;
    const double seconds = t.keyframes.back().time_s - t.keyframes.front().time_s + scene.haptics.settle_s;
    std::cout << "[7/7] haptic loop at " << scene.loop_rate_hz << " Hz playing the scripted trajectory (" << seconds
              << " s of " << (opt.simulated_time ? "simulated" : "real") << " time, m' = " << record.tuning.chosen_modes
              << ")\n";
    SessionOptions session;
    session.simulated_time = opt.simulated_time;
    session.wait = parse_loop_wait(opt.loop_wait);
    record.session = run_scripted_assembly(scene, pair.part(1).mesh, pair.part(2).mesh, pair.spectra.spacing,
                                           *loop_engine, record.tuning, session);
    if (record.session->priority.failed)
      note("could not raise the priority of " + std::to_string(record.session->priority.failed) +
           " threads for the loop (" + record.session->priority.reason + "); frames may be late on a busy machine");
    print_loop(scene, *record.session);
  } else {
    std::cout << "[7/7] the scene has no trajectory: no scripted assembly to run\n";
  }

  write_report(opt, record, start);
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
  cmd->add_option("--modes", opt->modes, "m': a fixed number of Fourier modes instead of the tuned one");
  cmd->add_option("--margin", opt->margin, "Tuning safety margin: p99 at most (1 - margin) of the frame budget")
      ->check(CLI::Range(0.0, 0.95));
  cmd->add_flag("--retune", opt->retune,
                "Measure m' and the strategies' errors again even when the tuning and strategy files match");
  cmd->add_option("--strategy", opt->strategy,
                  "Query strategy: auto (default: the lowest error that fits the frame, measured once per scene and "
                  "device against the exact reference; tricubic with --modes), tricubic, trilinear or exact-product")
      ->check(CLI::IsMember({"auto", "tricubic", "trilinear", "exact-product"}));
  cmd->add_flag("--simulated-time", opt->simulated_time,
                "Run the loop on simulated time: deterministic, as fast as the queries go, no timing meaning");
  cmd->add_option("--loop-wait", opt->loop_wait,
                  "How the loop waits for its tick: spin (default; keeps a core awake, fewest late frames on a "
                  "virtual machine) or sleep (frees the core between frames; SCHED_FIFO where allowed)")
      ->check(CLI::IsMember({"spin", "sleep"}));
  cmd->callback([opt] { run_main_job(*opt); });
}

}  // namespace snapfit::cli
