// The real-CAD benchmark: the six pairs of scenes/cad/ (STEP parts modelled with
// OpenCASCADE, tests/cad_pairs.h: a screw head seating on a rod, a ring slid 110 mm down a
// shaft, a square peg, a D-shaft, a plate with two pins, a filleted grooved shaft; 0-1 mm
// of clearance), each measured two ways:
//
// 1. Time to the first frame from cold caches: `snapfit run` on the pair's scene as a
//    child process with an empty SNAPFIT_CACHE_DIR, from its launch to its "[7/7]" line
//    (the haptic loop starts right after, behind its 50 warm-up queries). The run then
//    plays the scene's trajectory in real time; its summary.json gives the loop's misses
//    and the verdict.
// 2. bench_assembly's imprecise 6-DOF users (perf/imprecise_users.h) on simulated time,
//    with snapfit's engine as a second, warm run's loop rendered it (its query strategy and the
//    m' it started at; with --modes or without a cold run, bench_assembly's tricubic sum
//    at that m'), the scene's coupling, gain and rigid contact: per pair the success rate, the deepest true interpenetration of any trial
//    (mesh/interpenetration.h), the frames whose work took more CPU time than the budget,
//    and the frame work's p99. The fields and spectra come from the cache the cold run
//    left (or the default cache with --no-cold-run).
//
//   bench_real_cad --help lists its options.
// Writes trials.csv (one row per trial), summary.csv, summary.md, summary.json,
// charts.html, and per pair run/<pair>/ and run/<pair>_warm/ (the two runs' reports) and their logs.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>

#include "core/quantile.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/imprecise_users.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/tuning/accuracy.h"
#include "scheduler/haptics/rigid_contact.h"
#include "tests/cad_pairs.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

constexpr long kFallbackModes = 16384;  // bench_assembly's m'

struct Options {
  bool quick = false, cold_run = true;
  std::string device_spec, out_dir = "results/bench_real_cad", snapfit_cli;
  long trials = 20, seed = 1, stride = 10;
  long modes = 0;  // 0: the m' the warm run's loop started at, else kFallbackModes
  std::vector<std::string> pairs;
};

// build/perf/bench_real_cad -> build/snapfit.
std::string default_cli() {
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  return ec ? "snapfit" : (self.parent_path().parent_path() / "snapfit").string();
}

Options parse_options(int argc, char** argv) {
  Options o;
  o.snapfit_cli = default_cli();
  for (const test::CadPairInfo& p : test::cad_pairs()) o.pairs.push_back(p.name);
  bool no_cold_run = false;
  CLI::App app{"Real-CAD pairs: time to the first frame from cold caches and imprecise 6-DOF users' success, "
               "interpenetration and misses (see perf/bench_real_cad.cpp)",
               "bench_real_cad"};
  bench::add_common_options(app, o.quick, o.device_spec, o.out_dir,
                            "square_peg and d_shaft, no cold `snapfit run`, 1 user per pair at m' 4096, the default "
                            "cache (options given override)");
  const auto* trials = app.add_option("--trials", o.trials, "users per pair")->check(CLI::Range(1L, 100000L));
  app.add_option("--seed", o.seed, "the users' seed")->check(CLI::Range(0L, 1L << 30));
  const auto* modes =
      app.add_option("--modes", o.modes, "m' of the users' engine (0: the m' the warm run's loop started at, else 16384)")
          ->check(CLI::Range(0L, 1L << 24));
  app.add_option("--penetration-stride", o.stride, "every K-th frame's true interpenetration")
      ->check(CLI::Range(1L, 100000L));
  const auto* pairs =
      app.add_option("--pairs", o.pairs, "comma-separated pairs (scenes/cad/<pair>.json)")->delimiter(',');
  app.add_option("--snapfit", o.snapfit_cli, "the snapfit tool for the cold runs");
  app.add_flag("--no-cold-run", no_cold_run,
                                  "skip the cold `snapfit run` (no first-frame time; the users use the default cache)");
  bench::parse(app, argc, argv);
  o.cold_run = !no_cold_run && !o.quick;
  if (o.quick) {
    if (!*pairs) o.pairs = {"square_peg", "d_shaft"};  // the smallest grids
    if (!*trials) o.trials = 1;
    if (!*modes) o.modes = 4096;
  }
  return o;
}

const test::CadPairInfo& pair_named(const std::string& name) {
  for (const test::CadPairInfo& p : test::cad_pairs())
    if (p.name == name) return p;
  throw Error("--pairs: unknown pair '" + name + "'");
}

// What the cold `snapfit run` gave.
struct ColdRun {
  bool ran = false;
  double first_frame_s = NAN, total_s = NAN;
  long frames = 0, misses = 0;
  long modes = 0;         // the m' its loop started at
  std::string strategy;   // the query strategy its loop rendered (variant_name)
  std::string verdict;
};

// Runs `snapfit run` on the scene with `cache` as its cache folder (emptied first when
// `cold`); the time from launch to the "[7/7]" line, and the loop's misses and verdict
// from summary.json.
ColdRun cold_run(const Options& o, const std::string& scene_file, const fs::path& cache, const fs::path& report,
                 const fs::path& log_file, bool cold = true) {
  if (cold) fs::remove_all(cache);
  fs::create_directories(cache);
  fs::remove_all(report);
  const std::string command = "SNAPFIT_CACHE_DIR='" + cache.string() + "' '" + o.snapfit_cli + "' run '" + scene_file +
                              "' --out '" + report.string() + "' 2>&1";
  ColdRun r;
  const auto start = std::chrono::steady_clock::now();
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) throw Error("cannot start " + command);
  std::ofstream log(log_file);
  char line[4096];
  while (std::fgets(line, sizeof line, pipe)) {
    log << line << std::flush;
    if (std::isnan(r.first_frame_s) && std::string(line).rfind("[7/7]", 0) == 0)
      r.first_frame_s = seconds_since(start);
  }
  const int status = pclose(pipe);
  r.total_s = seconds_since(start);
  if (status != 0) throw Error("`snapfit run " + scene_file + "` failed (see " + log_file.string() + ")");
  std::ifstream in(report / "summary.json");
  const nlohmann::json s = nlohmann::json::parse(in);
  const nlohmann::json& loop = s.at("haptic_loop");
  r.ran = true;
  r.frames = loop.at("frames").get<long>();
  r.misses = loop.at("misses").get<long>();
  r.modes = loop.at("modes").at("start").get<long>();
  r.verdict = loop.at("verdict").get<std::string>();
  r.strategy = s.at("query_strategy").at("name").get<std::string>();
  return r;
}

struct PairResult {
  std::string pair;
  double clearance = 0, prepare_s = 0;
  long modes = 0;        // the users' m'
  std::string strategy;  // and their engine's variant
  ColdRun cold;
  std::vector<bench::TrialResult> trials;
};

// The variant named `strategy` among the strategies the loop chooses from
// (scheduler/tuning/accuracy.h); none named: bench_assembly's, the tricubic sum.
QueryVariant users_variant(const Scene& scene, const std::string& strategy) {
  if (strategy.empty()) return query_variant_for(scene, Interpolation::tricubic);
  for (const QueryVariant& v : accuracy_candidates(accuracy_base_variant(scene), true))
    if (variant_name(v) == strategy) return v;
  throw Error("the warm run's query strategy '" + strategy + "' is none of the loop's candidates");
}

// The users on one pair: the engine (the strategy and m' the warm run's loop rendered,
// else the tricubic sum at `modes`), the rigid contact and every trial.
PairResult run_users(const Options& o, const test::CadPairInfo& info, const Scene& loaded, long modes,
                     const std::string& strategy, const ComputeContext& ctx, const FftLibrary& fft,
                     bench::CsvFile& csv) {
  PairResult result;
  result.pair = info.name;
  result.clearance = info.clearance;
  result.modes = modes;
  Scene scene = loaded;
  scene.haptics.settle_s = 1;
  const auto start = std::chrono::steady_clock::now();
  PairOptions options;
  options.near_field = true;  // the warm run's strategy may be the near-far split
  options.note = [](const std::string& m) { std::cerr << "  " << m << "\n"; };
  const AssemblyPair pair = build_assembly_pair(scene, ctx, fft, options);
  const Mesh& m1 = pair.part(1).mesh;
  const Mesh& m2 = pair.part(2).mesh;
  const double spacing = pair.grids.spacing;
  const std::unique_ptr<QueryEngine> engine =
      make_query_engine(ctx, pair.spectra, users_variant(scene, strategy));
  result.strategy = variant_name(engine->variant());
  const auto rigid = rigid_contact_for(scene, m1, m2, spacing);
  const MeshDistanceIndex i1(m1), i2(m2);
  result.prepare_s = seconds_since(start);
  std::cout << "  users' engine (" << result.strategy << ", m' " << modes << ") and contact ready in " << bench::fixed(result.prepare_s, 1)
            << " s:" << std::flush;
  const bench::Fit fit{info.clearance, info.entry, info.engaged};
  std::mt19937 rng(static_cast<unsigned>(o.seed));
  const Pose assembled = scene.assembled_pose.value_or(Pose{});
  for (long t = 0; t < o.trials; ++t) {
    const bench::UserTrial user = bench::draw_trial(rng);
    scene.trajectory = bench::user_trajectory(assembled, info.entry, user, true);
    scene.part2.pose = scene.trajectory.keyframes.front().pose;
    bench::FrameWork work;
    work.wall_ms.reserve(8000), work.cpu_ms.reserve(8000);
    // The users leave the scene's trajectory: the region it gave still bounds part 1.
    const SessionResult run =
        bench::run_engine_trial(scene, m2, spacing, *engine, rigid, modes, work, region_guard(pair.region));
    const bench::TrialResult r =
        bench::measure(fit, scene.frame_budget_ms, run, work, m1, i1, m2, i2, static_cast<std::size_t>(o.stride));
    csv.row(info.name, info.clearance, t, r.success, r.inserted, r.position_error, r.lateral_error, r.axial_error,
            r.angle_error, r.max_penetration, r.peak_force, r.frame_p99_ms, r.frame_wall_p99_ms, r.misses, r.frames,
            user.lateral, user.tilt_deg, user.approach_offset, user.duration_s);
    result.trials.push_back(r);
    std::cout << (r.success ? " +" : r.inserted ? " ~" : " -") << std::flush;
  }
  std::cout << "\n";
  return result;
}

// One pair's line of summary.csv, summary.md and the JSON.
nlohmann::json summarise(const PairResult& p, bench::CsvFile& csv, std::ostringstream& md) {
  std::vector<double> pen, p99;
  double ok = 0, in = 0, misses = 0, frames = 0;
  for (const bench::TrialResult& r : p.trials) {
    pen.push_back(r.max_penetration), p99.push_back(r.frame_p99_ms);
    ok += r.success, in += r.inserted, misses += r.misses, frames += r.frames;
  }
  const double n = p.trials.size();
  const double deepest = quantile(pen, 1.0);
  csv.row(p.pair, p.clearance, bench::quoted(p.strategy), p.modes, n, ok / n, in / n, deepest, quantile(pen, 0.5), misses, frames, quantile(p99, 1.0),
          bench::finite_or_empty(p.cold.first_frame_s), bench::finite_or_empty(p.cold.total_s), p.cold.misses,
          p.cold.frames, p.cold.verdict, p.prepare_s);
  md << "| " << p.pair << " | " << p.clearance << " | " << p.strategy << ", " << p.modes << " | " << n << " | " << bench::fixed(100 * ok / n, 0) << " % | "
     << bench::fixed(100 * in / n, 0) << " % | " << bench::fixed(deepest, 3) << " | " << misses << " / " << frames
     << " | " << bench::fixed(quantile(p99, 1.0), 3) << " | "
     << (p.cold.ran ? bench::fixed(p.cold.first_frame_s, 0) + " s" : std::string("-")) << " | "
     << (p.cold.ran ? std::to_string(p.cold.misses) + " / " + std::to_string(p.cold.frames) + ", " + p.cold.verdict
                    : std::string("-"))
     << " |\n";
  return {{"pair", p.pair},
          {"clearance", p.clearance},
          {"strategy", p.strategy},
          {"modes", p.modes},
          {"trials", n},
          {"success_rate", ok / n},
          {"inserted_rate", in / n},
          {"max_penetration", bench::num(deepest)},
          {"median_max_penetration", bench::num(quantile(pen, 0.5))},
          {"user_misses", misses},
          {"user_frames", frames},
          {"frame_p99_ms", bench::num(quantile(p99, 1.0))},
          {"users_prepare_s", p.prepare_s},
          {"cold_run",
           p.cold.ran ? nlohmann::json{{"first_frame_s", p.cold.first_frame_s},
                                       {"total_s", p.cold.total_s},
                                       {"misses", p.cold.misses},
                                       {"frames", p.cold.frames},
                                       {"verdict", p.cold.verdict}}
                      : nlohmann::json(nullptr)}};
}

// Each pair's trials as points: the deepest interpenetration against the pair's index.
Chart depth_chart(const std::vector<PairResult>& results) {
  Chart c = bench::make_chart("Deepest true interpenetration per user (x: the pair, in the order of the table; the "
                              "dashed line: the 0.3 mm goal)",
                              "pair", "deepest interpenetration (mm)");
  for (std::size_t k = 0; k < results.size(); ++k) {
    Series s;
    s.label = results[k].pair;
    s.style = Series::Style::points;
    for (std::size_t t = 0; t < results[k].trials.size(); ++t) {
      s.x.push_back(k + 1 + 0.4 * (t + 0.5) / results[k].trials.size() - 0.2);
      s.y.push_back(results[k].trials[t].max_penetration);
    }
    c.series.push_back(s);
  }
  c.hlines.push_back({0.3, "goal 0.3 mm"});
  c.y_min = 0;
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_real_cad", [&] {
    const Options o = parse_options(argc, argv);
    const Device device = bench::loop_device(o.device_spec);  // as `snapfit run` picks it
    std::cout << "device " << describe_device(device.info) << "\n";
    const ComputeContext ctx = make_compute_context(device);
    const FftLibrary fft;
    const std::string load_start = bench::read_loadavg();
    fs::create_directories(o.out_dir);
    const fs::path out = fs::absolute(o.out_dir);
    bench::CsvFile trials_csv(out / "trials.csv",
                              "pair,clearance,trial,success,inserted,position_error,lateral_error,axial_error,"
                              "angle_error,max_penetration,peak_force,frame_p99_ms,frame_wall_p99_ms,misses,frames,"
                              "lateral_offset,tilt_deg,approach_offset,duration_s");
    std::vector<PairResult> results;
    const auto started = std::chrono::steady_clock::now();
    for (const std::string& name : o.pairs) {
      const test::CadPairInfo& info = pair_named(name);
      const std::string scene_file = "scenes/cad/" + name + ".json";
      std::cout << "== " << name << "\n";
      ColdRun cold, warm;
      if (o.cold_run) {
        const fs::path cache = out / "cache" / name;
        fs::create_directories(out / "run");
        cold = cold_run(o, scene_file, cache, out / "run" / name, out / "run" / (name + ".log"));
        std::cout << "  cold `snapfit run`: first frame after " << bench::fixed(cold.first_frame_s, 1) << " s, "
                  << cold.misses << " of " << cold.frames << " frames missed, " << cold.verdict << "\n";
        // The first run's loop starts on a safe strategy and measures the strategies after
        // it; a second run renders the measured choice, as every later run does: the users take that.
        warm = cold_run(o, scene_file, cache, out / "run" / (name + "_warm"), out / "run" / (name + "_warm.log"), false);
        std::cout << "  warm `snapfit run`: first frame after " << bench::fixed(warm.first_frame_s, 1) << " s, "
                  << warm.strategy << " at m' " << warm.modes << ", " << warm.misses << " of " << warm.frames
                  << " frames missed, " << warm.verdict << "\n";
        ::setenv("SNAPFIT_CACHE_DIR", cache.c_str(), 1);  // the users reuse its fields and spectra
      }
      const long modes = o.modes ? o.modes : warm.ran ? warm.modes : kFallbackModes;
      PairResult r = run_users(o, info, load_scene(scene_file), modes, o.modes ? "" : warm.strategy, ctx, fft,
                               trials_csv);
      r.cold = cold;
      results.push_back(std::move(r));
    }
    const double seconds = seconds_since(started);

    std::ostringstream md;
    bench::CsvFile scsv(out / "summary.csv",
                        "pair,clearance,strategy,modes,trials,success_rate,inserted_rate,max_penetration,median_max_penetration,"
                        "user_misses,user_frames,frame_p99_ms,first_frame_s,cold_run_s,run_misses,run_frames,"
                        "run_verdict,users_prepare_s");
    md << "| pair | clearance (mm) | strategy, m' | users | success | inserted | deepest interpenetration (mm) | users' misses / "
          "frames | frame work p99 (ms, max) | first frame, cold | `snapfit run`: misses / frames, verdict |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|\n";
    nlohmann::json pairs_json = nlohmann::json::array();
    for (const PairResult& r : results) pairs_json.push_back(summarise(r, scsv, md));
    std::cout << "\n"
              << md.str() << "\n"
              << results.size() << " pairs, " << o.trials << " users each, in " << bench::fixed(seconds, 0)
              << " s; load average " << load_start << " -> " << bench::read_loadavg() << "\n";
    std::ofstream(out / "summary.md") << md.str();
    nlohmann::json report = bench::run_record(argc, argv, device.info.name, load_start);
    report.update({{"trials", o.trials},
                   {"seed", o.seed},
                   {"modes", o.modes},
                   {"penetration_stride", o.stride},
                   {"cold_runs", o.cold_run},
                   {"seconds", seconds},
                   {"pairs", pairs_json}});
    bench::write_json(out / "summary.json", report);
    const std::string page = bench::write_charts(out, "bench_real_cad: real-CAD pairs, imprecise users",
                                                 bench::command_line(argc, argv), {depth_chart(results)});
    std::cout << "wrote " << o.out_dir << "/trials.csv, summary.csv, summary.md, summary.json and " << page << "\n";
    return 0;
  });
}
