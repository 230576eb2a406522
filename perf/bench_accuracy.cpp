// Error against run time: for a scene, a reference energy, force and torque at poses
// along its trajectory that is exact in rotation (every mode of the exact-rotation
// product made for each pose's rotation, scheduler/tuning/accuracy.h; checked against a double
// sum over the DTFT of part 2 by tests/test_exact_rotation.cpp), then for every setting
// the engine offers — m', interpolation (trilinear, tricubic) or the exact product,
// oversampling (zero padding 1.5, 2, 3), float (the OpenCL kernel) or double (the host
// reference evaluator at the same m') — the relative error of E, F and T against the time
// per query (for the exact product: the frame's line sums, the product made once).
// Relative error over the poses: sqrt(sum |x - ref|^2) / sqrt(sum |ref|^2). Charts: error
// against time (log-log) per quantity with the Pareto front and the point the auto-tuner
// picked for the scene's frame budget on this device. Last, `snapfit accuracy`'s summary
// (measure_accuracy): each strategy tuned for the budget, its frame p50/p99 and errors.
//
//   bench_accuracy --help lists its options.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>

#include "core/quantile.h"
#include "engine/query/query_engine.h"
#include "engine/query/reference_query.h"
#include "engine/runtime/device.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "pipeline/assembly_pair.h"
#include "report/accuracy_json.h"
#include "report/chart_spec.h"
#include "scheduler/tuning/accuracy.h"
#include "scheduler/tuning/engine_tuning.h"
#include "scheduler/haptics/trajectory.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

struct Row {
  double oversampling = 0;
  std::string interpolation, precision;
  std::size_t modes = 0;
  double ms = 0;  // p50 per query
  double err_energy = 0, err_force = 0, err_torque = 0;
  std::size_t flagged = 0;  // poses the engine refused (outside the alias-free box): no error figure
};

// Points not dominated in (time, error): the lower-left envelope, by increasing time.
std::vector<const Row*> pareto(const std::vector<Row>& rows, double Row::*err) {
  std::vector<const Row*> sorted;
  for (const Row& r : rows) sorted.push_back(&r);
  std::sort(sorted.begin(), sorted.end(), [](const Row* a, const Row* b) { return a->ms < b->ms; });
  std::vector<const Row*> front;
  double best = INFINITY;
  for (const Row* r : sorted)
    if (r->*err < best) best = r->*err, front.push_back(r);
  return front;
}

}  // namespace

// What every measured setting is compared with: the poses, the exact reference at each,
// and the host evaluator's outputs.
struct Inputs {
  const std::vector<Pose>& poses;
  const std::vector<QueryResult>& reference;
  ReferenceOptions ref_options;
  int repeats = 0;
};

// The device kernel at m': its errors over the poses and its p50 time per query.
Row float_row(QueryEngine& engine, const Inputs& in, double os, const std::string& scheme_name, std::size_t m,
              bool exact) {
  const std::vector<Pose>& poses = in.poses;
  Row f{os, scheme_name, "float", m};
  RelativeErrors fe;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const QueryResult r = engine.query(poses[i]);
    if (r.flags)
      ++f.flagged;
    else
      fe.add(r, in.reference[i]);
  }
  std::vector<double> times;
  for (int k = 0; k < in.repeats; ++k) {
    // The exact product: one pose, so the product is made once and the frame's line
    // sums are timed (what a background product leaves to the frame).
    const Pose& timed = poses[exact ? 0 : k % poses.size()];
    const auto t0 = std::chrono::steady_clock::now();
    engine.query(timed);
    times.push_back(1e3 * seconds_since(t0));
  }
  f.ms = quantile(times, 0.5);
  f.err_energy = fe.relative(0), f.err_force = fe.relative(1), f.err_torque = fe.relative(2);
  return f;
}

// The host reference evaluator at the same m'.
Row double_row(const PairSpectra& s, const std::vector<std::size_t>& order, const Inputs& in, double os,
               Interpolation scheme, const std::string& scheme_name, std::size_t m) {
  const std::vector<Pose>& poses = in.poses;
  Row d{os, scheme_name, "double", m};
  RelativeErrors de;
  std::vector<double> dtimes;
  ReferenceOptions o = in.ref_options;
  o.interpolation = scheme;
  o.modes = m;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const QueryResult r = reference_query(s, poses[i], o, &order);
    if (r.flags)
      ++d.flagged;
    else
      de.add(r, in.reference[i]);
    dtimes.push_back(1e3 * r.seconds);
  }
  d.ms = quantile(dtimes, 0.5);
  d.err_energy = de.relative(0), d.err_force = de.relative(1), d.err_torque = de.relative(2);
  return d;
}

// One strategy (0 trilinear, 1 tricubic, 2 the exact product) at one oversampling: its
// ladder of m' in float and, but for the exact product, in double.
void measure_strategy(const ComputeContext& ctx, const PairSpectra& s, const Inputs& in,
                      const QueryVariant& scene_variant, double os, int strategy, std::size_t max_ladder,
                      std::size_t tuned_modes, std::vector<Row>& rows, nlohmann::json& flagged_settings) {
  // The exact product's frame only sums lines: its ladder goes 4x further.
  const std::size_t exact_ladder = 4 * max_ladder;
  const std::vector<std::size_t> order = mode_order(s);
  const bool exact = strategy == 2;
  if (exact && (scene_variant.translation_only || s.part2.deconvolved_width == 0)) return;
  const Interpolation scheme = strategy == 0 ? Interpolation::trilinear : Interpolation::tricubic;
  const std::string scheme_name = exact ? "exact-product" : strategy == 0 ? "trilinear" : "tricubic";
  QueryVariant variant = scene_variant;
  variant.interpolation = scheme;
  if (exact) variant = bench::exact_reference_variant(variant, exact_ladder);
  auto engine = make_query_engine(ctx, s, variant);
  std::vector<std::size_t> ladder;
  for (std::size_t m = 1024; m <= std::min(exact ? exact_ladder : max_ladder, engine->max_modes()); m *= 2)
    ladder.push_back(m);
  if (os == 2.0 && strategy == 1) {  // the tuned point, measured like the others
    ladder.push_back(tuned_modes);
    std::sort(ladder.begin(), ladder.end());
    ladder.erase(std::unique(ladder.begin(), ladder.end()), ladder.end());
  }
  for (std::size_t m : ladder) {
    engine->set_modes(m);
    // float: the device kernel.
    const Row f = float_row(*engine, in, os, scheme_name, m, exact);
    if (!f.flagged) rows.push_back(f);
    if (exact) {
      std::printf("os %.1f %-13s m' %7zu  float %8.3f ms  E %.2e F %.2e T %.2e\n", os, scheme_name.c_str(), m, f.ms,
                  f.err_energy, f.err_force, f.err_torque);
      continue;
    }
    // double: the host reference evaluator at the same m' (skipped where it is slow).
    const Row d = double_row(s, order, in, os, scheme, scheme_name, m);
    if (!d.flagged) rows.push_back(d);
    if (f.flagged) {
      flagged_settings.push_back(
          {{"oversampling", os}, {"interpolation", scheme_name}, {"modes", m}, {"flagged_poses", f.flagged}});
      std::printf("os %.1f %-9s m' %7zu  %zu of %zu poses outside this FFT box's alias-free range: no figure\n", os,
                  scheme_name.c_str(), m, f.flagged, in.poses.size());
    } else {
      std::printf("os %.1f %-9s m' %7zu  float %8.3f ms  E %.2e F %.2e T %.2e | double %8.3f ms  E %.2e\n", os,
                  scheme_name.c_str(), m, f.ms, f.err_energy, f.err_force, f.err_torque, d.ms, d.err_energy);
    }
  }
}

// Relative error of one output against time per query, per setting, with the Pareto
// front (into `front`) and the auto-tuner's point.
Chart error_chart(const char* name, double Row::*err, const std::vector<Row>& rows,
                  const std::vector<double>& oversamplings, const std::string& device_name, std::size_t tuned_modes,
                  nlohmann::json& front_json) {
  Chart c = bench::make_chart(std::string("Relative ") + name + " error against time per query (" + device_name + ")",
                              "ms per query (p50)", std::string("relative ") + name + " error", true, true);
  for (double os : oversamplings)
    for (const char* scheme : {"trilinear", "tricubic", "exact-product"})
      for (const char* precision : {"float", "double"}) {
        Series s{
            std::string(scheme) + " " + precision + " x" + bench::fmt(os, 6), {}, {}, Series::Style::line_points, ""};
        for (const Row& r : rows)
          if (r.oversampling == os && r.interpolation == scheme && r.precision == precision && r.*err > 0)
            s.x.push_back(r.ms), s.y.push_back(r.*err);
        if (!s.x.empty()) c.series.push_back(s);
      }
  Series front{"Pareto front", {}, {}, Series::Style::line, ""};
  front.color = "#000000";
  nlohmann::json jf = nlohmann::json::array();
  for (const Row* r : pareto(rows, err)) {
    if (!(r->*err > 0)) continue;
    front.x.push_back(r->ms), front.y.push_back(r->*err);
    jf.push_back({{"oversampling", r->oversampling},
                  {"interpolation", r->interpolation},
                  {"precision", r->precision},
                  {"modes", r->modes},
                  {"ms_p50", r->ms},
                  {"error", r->*err}});
  }
  c.series.push_back(front);
  front_json = jf;
  for (const Row& r : rows)
    if (r.oversampling == 2.0 && r.interpolation == "tricubic" && r.precision == "float" && r.modes == tuned_modes)
      c.markers.push_back(Marker{r.ms, r.*err, "auto-tuner, 1 ms budget"});
  c.hlines.push_back(HLine{1e-2, "1%"});
  return c;
}

// What the budget buys (snapfit accuracy): each strategy tuned for it and measured.
nlohmann::json at_budget(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                         const std::string& device_name, bool quick) {
  AccuracyOptions at_options;
  at_options.budget_ms = scene.frame_budget_ms;
  at_options.poses = quick ? 3 : 24;
  at_options.repetitions = quick ? 100 : 400;
  const AccuracyReport budget_report = measure_accuracy(ctx, scene, spectra, at_options);
  nlohmann::json at_budget = nlohmann::json::array();
  std::cout << "at the " << scene.frame_budget_ms << " ms budget on " << device_name << " (" << budget_report.poses
            << " poses):\n";
  for (const StrategyAccuracy& a : budget_report.strategies) {
    std::printf("  %-50s m' %7zu  p50 %.3f ms  p99 %.3f ms  E %.2e F %.2e T %.2e%s\n", a.name.c_str(), a.modes,
                a.frame_ms_p50, a.frame_ms_p99, a.energy_error, a.force_error, a.torque_error,
                a.fits ? "" : "  (does not fit)");
    std::printf("  %-50s estimate covers E %.0f%% F %.0f%% T %.0f%% of poses, median estimate / error %.2g %.2g %.2g\n",
                "", 100 * a.estimate_coverage[0], 100 * a.estimate_coverage[1], 100 * a.estimate_coverage[2],
                a.estimate_ratio_median[0], a.estimate_ratio_median[1], a.estimate_ratio_median[2]);
    at_budget.push_back(strategy_accuracy_json(a));
  }
  return at_budget;
}

// The pair's spectra at each oversampling (pipeline stage 3, from the spectra cache when present).
std::map<double, PairSpectra> spectra_per_oversampling(const AssemblyPair& pair, const ComputeContext& ctx,
                                                       const FftLibrary& fft,
                                                       const std::vector<double>& oversamplings) {
  std::map<double, PairSpectra> spectra;
  for (double os : oversamplings) {
    AssemblyPair at = pair;
    PairOptions options;
    options.spectrum.oversampling = os;
    options.note = [](const std::string&) {};
    compute_assembly_spectra(at, ctx, fft, options);
    const auto& d = at.spectra.dims;
    std::cout << "oversampling " << os << ": FFT grid " << d[0] << " x " << d[1] << " x " << d[2]
              << (at.spectra_from_cache ? " (cached)" : "") << "\n";
    spectra.emplace(os, std::move(at.spectra));
  }
  return spectra;
}

int main(int argc, char** argv) {
  return bench::guarded_main("bench_accuracy", [&] {
    std::string scene_path = "scenes/default.json", out_dir = "results/bench_accuracy";
    bool quick = false;
    CLI::App app{
        "Error against run time of every engine setting, against a reference exact in rotation, and "
        "`snapfit accuracy`'s summary",
        "bench_accuracy"};
    bench::add_quick_and_out(app, quick, out_dir, "oversampling 2 only, 3 poses, m' <= 16384, fewer repeats");
    app.add_option("--scene", scene_path, "scene (needs a trajectory)");
    bench::parse(app, argc, argv);
    const std::string load_start = bench::read_loadavg();
    const Scene scene = load_scene(scene_path);
    if (scene.trajectory.keyframes.empty()) throw Error(scene_path + ": needs a trajectory for its poses");
    const Device device = select_device(device_spec_from(""));
    std::cout << "device " << describe_device(device.info) << "\n";
    const FftLibrary fft;
    const ComputeContext ctx = make_compute_context(device);
    const AssemblyPair pair = build_assembly_pair(scene, ctx, fft);
    const QueryVariant scene_variant = query_variant_for(scene, Interpolation::tricubic);
    const bool torque = scene_variant.torque;

    // Poses: along the trajectory, every 0.5 s (3 of them with --quick), all in the grid.
    std::vector<Pose> poses;
    const Trajectory& t = scene.trajectory;
    for (double s = t.keyframes.front().time_s + 0.5; s <= t.keyframes.back().time_s + 1e-9; s += quick ? 1.5 : 0.5)
      poses.push_back(trajectory_pose(t, s));
    const std::vector<double> oversamplings = quick ? std::vector<double>{2.0} : std::vector<double>{1.5, 2.0, 3.0};
    const std::size_t max_ladder = quick ? 16384 : 262144;
    const int repeats = quick ? 30 : 200;

    const std::map<double, PairSpectra> spectra = spectra_per_oversampling(pair, ctx, fft, oversamplings);
    const auto ref_start = std::chrono::steady_clock::now();
    // Exact in rotation (tests/test_exact_rotation.cpp checks it).
    const std::vector<QueryResult> reference = bench::exact_references(
        ctx, pair.spectra, scene_variant, poses, [&](std::size_t i, const QueryResult& r, double s) {
          if (r.flags) throw Error("reference pose " + std::to_string(i) + " is outside the grid");
          std::cout << "reference " << i + 1 << "/" << poses.size() << ": E = " << r.energy << " (" << s << " s, "
                    << r.modes << " modes)\n";
        });
    const double ref_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - ref_start).count();
    ReferenceOptions ref_options;
    ref_options.force = scene.outputs.force;
    ref_options.torque = torque;

    // The auto-tuner's point for the scene's budget (tricubic, oversampling 2, float).
    auto tuned_engine = make_query_engine(ctx, pair.spectra, scene_variant);
    const TuningKey key =
        tuning_key_for(device.info, scene_variant, pair.spectra, scene.frame_budget_ms, 0.25, scene.loop_rate_hz);
    TuneOptions tune;
    if (quick) tune.repetitions = 100;
    const EngineTuning tuned = tune_engine(*tuned_engine, key, sample_trajectory(t, 100.0), tune, false, nullptr);
    std::cout << "auto-tuner: m' = " << tuned.result.chosen_modes
              << (tuned.from_file ? " (tuning file)" : " (measured)") << "\n";

    std::vector<Row> rows;
    nlohmann::json flagged_settings = nlohmann::json::array();
    const Inputs in{poses, reference, ref_options, repeats};
    for (double os : oversamplings)
      for (int strategy = 0; strategy < 3; ++strategy)
        measure_strategy(ctx, spectra.at(os), in, scene_variant, os, strategy, max_ladder, tuned.result.chosen_modes,
                         rows, flagged_settings);

    fs::create_directories(out_dir);
    bench::CsvFile csv(fs::path(out_dir) / "accuracy.csv",
                       "oversampling,interpolation,precision,modes,ms_p50,err_energy,err_force,err_torque");
    nlohmann::json jrows = nlohmann::json::array();
    for (const Row& r : rows) {
      csv.row(r.oversampling, r.interpolation, r.precision, r.modes, r.ms, r.err_energy, r.err_force, r.err_torque);
      jrows.push_back({{"oversampling", r.oversampling},
                       {"interpolation", r.interpolation},
                       {"precision", r.precision},
                       {"modes", r.modes},
                       {"ms_p50", r.ms},
                       {"err_energy", r.err_energy},
                       {"err_force", r.err_force},
                       {"err_torque", r.err_torque}});
    }

    const std::array<std::pair<const char*, double Row::*>, 3> quantities = {
        {{"energy", &Row::err_energy}, {"force", &Row::err_force}, {"torque", &Row::err_torque}}};
    nlohmann::json fronts;
    std::vector<Chart> charts;
    for (const auto& [name, err] : quantities) {
      if (std::string(name) == "torque" && !torque) continue;
      charts.push_back(
          error_chart(name, err, rows, oversamplings, device.info.name, tuned.result.chosen_modes, fronts[name]));
    }
    const nlohmann::json budget = at_budget(ctx, scene, pair.spectra, device.info.name, quick);
    nlohmann::json report = bench::run_record(argc, argv, device.info.name, load_start);
    report.update({{"scene", scene_path},
                   {"poses", poses.size()},
                   {"reference",
                    {{"method", "exact-rotation product, every mode, made for each pose's rotation"},
                     {"oversampling", 2.0},
                     {"modes", reference.front().modes},
                     {"seconds_total", ref_seconds}}},
                   {"at_budget", budget},
                   {"tuned_modes", tuned.result.chosen_modes},
                   {"rows", jrows},
                   {"outside_alias_free_box", flagged_settings},
                   {"pareto", fronts}});
    std::ofstream(fs::path(out_dir) / "accuracy.json") << report.dump(2) << "\n";
    const std::string page = bench::write_charts(out_dir, "bench_accuracy: error against time per query",
                                                 bench::command_line(argc, argv), charts);
    std::cout << "wrote " << out_dir << "/accuracy.csv, accuracy.json and " << page << "\n";
    return 0;
  });
}
