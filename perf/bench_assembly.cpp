// The assembly benchmark: scripted insertions by an imprecise user, so that the geometry
// has to do the aligning, for snapfit (6-DOF and translation-only), Voxmap PointShell
// (scheduler/vps/vps_method.h) and its constraint hybrid (scheduler/vps/vps_hybrid.h, with the
// parts' analytic faces) at several voxel sizes, in the same haptic loop.
//
// Cells: the peg in its blind hole (scenes/peg_hole_clearance_0p5.json with the hole's
// clearance set to each of --clearances) and the three-peg pair (scenes/three_pegs.json,
// zero clearance). Each trial (seeded) ends the device's target off the assembled pose
// by a lateral offset of 0-1 mm in a random direction and a tilt of 0-3 degrees about a
// random horizontal axis (none for translation-only), approaching from a random side
// (0-4 mm off the axis, 8-12 mm up) over 1.5-3.5 s, then 1 s of settling. The loop runs
// on simulated time (trials do not wait in real time); each frame's query is timed as the
// loop thread's CPU time (and on the wall clock), and a frame whose query took more CPU
// time than the scene's budget counts as a miss.
//
// The users and their judging are shared with perf/bench_real_cad.cpp (perf/imprecise_users.h).
// Per trial: inserted (axial error <= the scene's position tolerance), success (inserted,
// lateral error <= tolerance + clearance, angle error <= tolerance + the hole's play
// atan(2 c / depth)), final position and angle errors, the largest true
// interpenetration (the deepest vertex of either part inside the other by exact
// point-to-mesh signed distance, mesh/mesh_distance.h, every --penetration-stride
// frames and at the last), the largest change of the sent force between frames, the RMS
// of its second difference (high-frequency content), and frame-work p99 and misses.
//
//   bench_assembly --help lists its options.
// Writes trials.csv (one row per trial), summary.csv and summary.md (per cell),
// wrench_vs_depth.csv (one trial per method), summary.json and charts.html.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <sstream>
#include <time.h>

#include "core/quantile.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "mesh/mesh_distance.h"
#include "mesh/procedural/procedural_parts.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/imprecise_users.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/assembly_session.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/rigid_contact.h"
#include "scheduler/vps/vps_hybrid.h"
#include "scheduler/vps/vps_method.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

struct BenchMethod {
  std::string name;  // "snapfit-6dof", "snapfit-translation", "vps-0.25"
  enum Kind { six_dof, translation, vps, vps_hybrid } kind = six_dof;
  bool voxel_based() const { return kind == vps || kind == vps_hybrid; }
  double voxel = 0;
};

struct Cell {
  std::string pair;  // "peg-in-hole" or "three-pegs"
  Scene scene;
  bench::Fit fit;
};

Scene translation_scene(Scene s) {
  s.motion = Motion::translation;
  s.outputs = Outputs{true, true, false};
  s.part2.pose.rotation = Eigen::Quaterniond::Identity();
  if (s.assembled_pose) s.assembled_pose->rotation = Eigen::Quaterniond::Identity();
  return s;
}

// The command line.
struct Options {
  bool quick = false, three_pegs = true, contact = true;
  std::string device_spec, out_dir = "results/bench_assembly";
  long trials = 20, seed = 1, modes = 16384, stride = 10;
  std::vector<double> clearances = {0, 0.02, 0.05, 0.1, 0.25, 0.5, 1}, voxels = {0.1, 0.25, 0.5};
  std::vector<std::string> methods = {"snapfit", "translation", "vps"};
  std::optional<double> geometry_strength, lambda_in, contact_stiffness;  // overrides of the scenes' values
  std::string hybrid_json;  // the scenes' vps.hybrid section, as a scene file gives it
};

Options parse_options(int argc, char** argv) {
  Options o;
  double geometry_strength = 0, lambda_in = 0, contact_stiffness = 0;
  bool no_three_pegs = false, no_contact = false;
  CLI::App app{
      "Scripted imprecise-user insertions: success, errors and true interpenetration against clearance, for "
      "snapfit (6-DOF, translation-only) and Voxmap PointShell (see perf/bench_assembly.cpp)",
      "bench_assembly"};
  bench::add_common_options(app, o.quick, o.device_spec, o.out_dir,
                            "clearance 0.5 only (the shipped scene), no three-peg pair, 2 trials, VPS at 0.25 mm, m' "
                            "4096 (options given override)");
  const auto* trials =
      app.add_option("--trials", o.trials, "trials per cell and method")->check(CLI::Range(1L, 100000L));
  app.add_option("--seed", o.seed, "the users' seed")->check(CLI::Range(0L, 1L << 30));
  const auto* modes = app.add_option("--modes", o.modes, "m' of snapfit's engine")->check(CLI::Range(1L, 1L << 24));
  app.add_option("--penetration-stride", o.stride, "every K-th frame's true interpenetration")
      ->check(CLI::Range(1L, 100000L));
  const auto* clearances = app.add_option("--clearances", o.clearances, "comma-separated clearances of the peg, mm")
                               ->delimiter(',')
                               ->check(CLI::NonNegativeNumber);
  const auto* voxels = app.add_option("--voxels", o.voxels, "comma-separated VPS voxel sizes")
                           ->delimiter(',')
                           ->check(cli::positive_number());
  app.add_option("--methods", o.methods, "comma-separated methods: snapfit, translation, vps, vps_hybrid")
      ->delimiter(',');
  const auto* strength = app.add_option("--geometry-strength", geometry_strength,
                                        "overrides the scenes' haptics.geometry_strength (snapfit's methods)")
                             ->check(CLI::NonNegativeNumber);
  const auto* lambda = app.add_option("--lambda-in", lambda_in,
                                      "overrides the scenes' descriptor.lambda_in (the penalty factor, lambda_out 1)")
                           ->check(CLI::NonNegativeNumber);
  const auto* stiffness =
      app.add_option("--contact-stiffness", contact_stiffness, "overrides haptics.contact_stiffness_n_per_mm3 (N/mm^3)")
          ->check(CLI::NonNegativeNumber);
  app.add_option("--hybrid", o.hybrid_json,
                 "the scenes' vps.hybrid section for vps_hybrid, as JSON (e.g. '{\"x_full\": 0.9}'; docs/scenes.md)");
  app.add_flag("--no-three-pegs", no_three_pegs, "the peg in the hole only");
  app.add_flag("--no-contact", no_contact,
               "seed 000's energy alone, without the rigid contact (scheduler/haptics/rigid_contact.h)");
  bench::parse(app, argc, argv);
  o.three_pegs = !no_three_pegs && !o.quick;
  o.contact = !no_contact;
  if (o.quick) {
    if (!*trials) o.trials = 2;
    if (!*modes) o.modes = 4096;
    if (!*clearances) o.clearances = {0.5};
    if (!*voxels) o.voxels = {0.25};
  }
  if (*strength) o.geometry_strength = geometry_strength;
  if (*lambda) o.lambda_in = lambda_in;
  if (*stiffness) o.contact_stiffness = contact_stiffness;
  return o;
}

// The methods named on the command line; the voxel-based ones once per voxel size.
std::vector<BenchMethod> methods_from(const std::vector<std::string>& names, const std::vector<double>& voxels) {
  std::vector<BenchMethod> methods;
  for (const std::string& m : names) {
    if (m == "snapfit")
      methods.push_back({"snapfit-6dof", BenchMethod::six_dof, 0});
    else if (m == "translation")
      methods.push_back({"snapfit-translation", BenchMethod::translation, 0});
    else if (m == "vps")
      for (double v : voxels) methods.push_back({"vps-" + bench::fixed(v, 2), BenchMethod::vps, v});
    else if (m == "vps_hybrid")
      for (double v : voxels) methods.push_back({"vps_hybrid-" + bench::fixed(v, 2), BenchMethod::vps_hybrid, v});
    else
      throw Error("--methods: unknown method '" + m + "' (expected snapfit, translation, vps, vps_hybrid)");
  }
  return methods;
}

// The scene with --hybrid's vps.hybrid section, read by the scene reader as a file's is.
Scene with_hybrid(Scene scene, const std::string& hybrid_json) {
  if (hybrid_json.empty()) return scene;
  nlohmann::json j = nlohmann::json::parse(scene_to_json(scene));
  try {
    j["vps"]["hybrid"] = nlohmann::json::parse(hybrid_json);
  } catch (const nlohmann::json::exception& e) {
    throw Error("--hybrid: not JSON: " + std::string(e.what()));
  }
  return parse_scene(j.dump(), "--hybrid");
}

// The pairs the users assemble: the peg at each clearance, then the three-peg pair.
std::vector<Cell> make_cells(const Options& o) {
  std::vector<Cell> cells;
  for (double c : o.clearances) {
    Cell cell;
    cell.pair = "peg-in-hole";
    cell.fit.clearance = c;
    cell.scene = with_hybrid(load_scene("scenes/peg_hole_clearance_0p5.json"), o.hybrid_json);
    cell.scene.part1.procedural->numbers["clearance"] = c;
    cell.scene.name = "peg in hole, clearance " + bench::fixed(c, 2) + " mm";
    cell.scene.part2.pose = Pose{};
    cell.fit.entry = 20;  // the hole's depth: the peg's bottom meets the block's top 20 mm above home
    cell.fit.engaged = 20;
    cells.push_back(cell);
  }
  if (o.three_pegs) {
    Cell cell;
    cell.pair = "three-pegs";
    cell.scene = with_hybrid(load_scene("scenes/three_pegs.json"), o.hybrid_json);
    cell.scene.part2.pose = Pose{};
    cell.fit.entry = 14;   // above the tallest peg (12 mm) and its fillet
    cell.fit.engaged = 8;  // the shortest peg's height
    cells.push_back(cell);
  }
  return cells;
}

// A method's model of one scene: snapfit's pair, engine and rigid contact, or VPS's
// voxel model (with the analytic faces for the hybrid).
struct Model {
  std::optional<AssemblyPair> pair;
  std::unique_ptr<QueryEngine> engine;
  std::optional<VpsModel> vps;
  std::optional<HybridModel> hybrid;
  std::shared_ptr<const RigidContactModel> rigid;
  CouplingParams coupling;
};

Model build_model(Scene& scene, const BenchMethod& method, const Cell& cell, const AssemblyPair& parts,
                  const std::optional<ComputeContext>& ctx, const std::optional<FftLibrary>& fft, bool contact) {
  const Mesh& m1 = parts.part(1).mesh;
  const Mesh& m2 = parts.part(2).mesh;
  const double spacing = parts.grids.spacing;
  Model model;
  if (method.voxel_based()) {
    scene.vps.voxel_size = method.voxel;
    model.coupling = coupling_for(scene, m2);
    model.vps = vps_model_for(scene, m1, m2, spacing, model.coupling);
    if (method.kind == BenchMethod::vps_hybrid) {
      std::vector<AnalyticFace> f1 = parts.part(1).faces, f2 = parts.part(2).faces;
      if (f1.empty() || f2.empty())
        std::cout << "  (" << cell.pair << ": no analytic faces, " << method.name << " runs as plain VPS)\n";
      else
        model.hybrid = hybrid_model(*model.vps, std::move(f1), std::move(f2), model.coupling, hybrid_params_for(scene));
    }
  } else {
    PairOptions options;
    options.note = [](const std::string& m) { std::cerr << "  " << m << "\n"; };
    model.pair = build_assembly_pair(scene, *ctx, *fft, options);
    model.engine = make_query_engine(*ctx, model.pair->spectra, query_variant_for(scene, Interpolation::tricubic));
    scene.haptics.contact = scene.haptics.contact && contact;
    model.rigid = rigid_contact_for(scene, m1, m2, spacing);
  }
  return model;
}

// One user's insertion with the method's model, on simulated time; each frame's work into `work`.
SessionResult run_trial(const Scene& scene, const Mesh& part2, double spacing, Model& model, const BenchMethod& method,
                        long modes, bench::FrameWork& work) {
  SessionOptions options;
  options.simulated_time = true;
  SessionResult run;
  if (model.hybrid) {
    HybridState state = hybrid_state_for(*model.hybrid);  // each user starts disengaged
    run = run_scripted_session(scene, part2, spacing, vps_loop_config(scene, *model.vps, model.coupling),
                               bench::timed(hybrid_evaluator(*model.hybrid, state), work), options);
  } else if (method.voxel_based()) {
    run = run_scripted_session(scene, part2, spacing, vps_loop_config(scene, *model.vps, model.coupling),
                               bench::timed(vps_evaluator(*model.vps), work), options);
  } else {
    run = bench::run_engine_trial(scene, part2, spacing, *model.engine, model.rigid, modes, work);
  }
  return run;
}

struct Summary {
  std::string pair, method;
  double clearance = 0;
  std::vector<bench::TrialResult> trials;
};

// Where the trials go: trials.csv, and for trial 0 of the peg at the middle clearance the
// wrench against depth (wrench_vs_depth.csv and the charts).
struct TrialFiles {
  bench::CsvFile csv, depth_csv;
  double depth_clearance = 0;
  std::map<std::string, std::vector<std::pair<double, double>>> force_depth, torque_depth;  // method -> (depth, value)
};

void write_trial(TrialFiles& out, const Cell& cell, const BenchMethod& method, const Scene& scene, long t,
                 const bench::UserTrial& user, const SessionResult& run, const bench::TrialResult& r) {
  out.csv.row(cell.pair, method.name, cell.fit.clearance, t, r.success, r.inserted, r.position_error, r.lateral_error,
              r.axial_error, r.angle_error, r.max_penetration, r.max_force_step, r.force_hf_rms, r.peak_force,
              r.frame_p99_ms, r.frame_wall_p99_ms, r.misses, r.frames, user.lateral,
              method.kind == BenchMethod::translation ? 0.0 : user.tilt_deg, user.approach_offset, user.duration_s);
  if (t == 0 && cell.pair == "peg-in-hole" && cell.fit.clearance == out.depth_clearance) {
    for (const FrameRecord& f : run.loop.log) {
      const double depth = scene.assembled_pose->translation.z() + cell.fit.entry - f.part.translation.z();
      out.depth_csv.row(cell.pair, method.name, cell.fit.clearance, t, f.time_s, depth, f.sent.force.norm(),
                        f.sent.torque.norm());
      out.force_depth[method.name].push_back({depth, f.sent.force.norm()});
      out.torque_depth[method.name].push_back({depth, f.sent.torque.norm()});
    }
  }
}

// Every trial of one method on one cell.
Summary run_method(const Options& o, TrialFiles& out, const Cell& cell, const BenchMethod& method,
                   const AssemblyPair& parts, const MeshDistanceIndex& i1, const MeshDistanceIndex& i2,
                   const std::optional<ComputeContext>& ctx, const std::optional<FftLibrary>& fft) {
  const Mesh& m1 = parts.part(1).mesh;
  const Mesh& m2 = parts.part(2).mesh;
  const double spacing = parts.grids.spacing;
  Scene scene = method.kind == BenchMethod::translation ? translation_scene(cell.scene) : cell.scene;
  scene.haptics.settle_s = 1;
  if (o.geometry_strength) scene.haptics.geometry_strength = *o.geometry_strength;
  if (o.lambda_in) scene.descriptor.lambda_in = *o.lambda_in;
  if (o.contact_stiffness) scene.haptics.contact_stiffness_n_per_mm3 = *o.contact_stiffness;
  const auto build_start = std::chrono::steady_clock::now();
  Model model = build_model(scene, method, cell, parts, ctx, fft, o.contact);
  std::cout << "  " << bench::padr(method.name, 20) << " built in "
            << bench::fixed(seconds_since(build_start), 1) << " s" << std::flush;
  Summary summary{cell.pair, method.name, cell.fit.clearance, {}};
  std::mt19937 rng(static_cast<unsigned>(o.seed));  // the same users for every method of a cell
  for (long t = 0; t < o.trials; ++t) {
    const bench::UserTrial user = bench::draw_trial(rng);
    scene.trajectory = bench::user_trajectory(scene.assembled_pose.value_or(Pose{}), cell.fit.entry, user,
                                       method.kind != BenchMethod::translation);
    scene.part2.pose = scene.trajectory.keyframes.front().pose;
    bench::FrameWork work;
    work.wall_ms.reserve(8000), work.cpu_ms.reserve(8000);
    const SessionResult run = run_trial(scene, m2, spacing, model, method, o.modes, work);
    const bench::TrialResult r =
        bench::measure(cell.fit, cell.scene.frame_budget_ms, run, work, m1, i1, m2, i2, static_cast<std::size_t>(o.stride));
    write_trial(out, cell, method, scene, t, user, run, r);
    summary.trials.push_back(r);
    std::cout << (r.success ? " +" : r.inserted ? " ~" : " -") << std::flush;
  }
  std::cout << "\n";
  return summary;
}

// One cell and method's line of the summary: summary.csv, summary.md and the JSON; the
// peg's success rate into `success_series`.
nlohmann::json summarise(const Summary& s, bench::CsvFile& scsv, std::ostringstream& md,
                         std::map<std::string, Series>& success_series) {
  std::vector<double> pos, ang, pen, step, hf, p99, wall99;
  double ok = 0, in = 0, misses = 0;
  for (const bench::TrialResult& r : s.trials) {
    pos.push_back(r.position_error), ang.push_back(r.angle_error), pen.push_back(r.max_penetration);
    step.push_back(r.max_force_step), hf.push_back(r.force_hf_rms), p99.push_back(r.frame_p99_ms);
    wall99.push_back(r.frame_wall_p99_ms);
    ok += r.success, in += r.inserted, misses += r.misses;
  }
  const double n = s.trials.size();
  scsv.row(s.pair, s.method, s.clearance, n, ok / n, in / n, quantile(pos, 0.5), quantile(ang, 0.5), quantile(pen, 0.5),
           quantile(pen, 1.0), quantile(step, 0.5), quantile(hf, 0.5), quantile(p99, 1.0), quantile(wall99, 1.0),
           misses);
  md << "| " << s.pair << " | " << s.method << " | " << s.clearance << " | " << n << " | "
     << bench::fixed(100 * ok / n, 0) << " % | " << bench::fixed(100 * in / n, 0) << " % | "
     << bench::fixed(quantile(pos, 0.5), 3) << " | " << bench::fixed(quantile(ang, 0.5), 2) << " | "
     << bench::fixed(quantile(pen, 0.5), 3) << " / " << bench::fixed(quantile(pen, 1.0), 3) << " | "
     << bench::fixed(quantile(step, 0.5), 3) << " | " << bench::fixed(quantile(p99, 1.0), 3) << " | " << misses
     << " |\n";
  const nlohmann::json j = {{"pair", s.pair},
                            {"method", s.method},
                            {"clearance", s.clearance},
                            {"trials", n},
                            {"success_rate", ok / n},
                            {"inserted_rate", in / n},
                            {"median_position_error", bench::num(quantile(pos, 0.5))},
                            {"median_angle_error", bench::num(quantile(ang, 0.5))},
                            {"max_penetration", bench::num(quantile(pen, 1.0))},
                            {"frame_p99_ms", bench::num(quantile(p99, 1.0))},
                            {"frame_wall_p99_ms", bench::num(quantile(wall99, 1.0))},
                            {"misses", misses}};
  if (s.pair == "peg-in-hole") {
    Series& series = success_series[s.method];
    series.label = s.method;
    series.x.push_back(std::max(s.clearance, 0.01));  // log axis: clearance 0 drawn at 0.01 mm
    series.y.push_back(100 * ok / n);
  }
  return j;
}

Chart depth_chart(const std::string& what, const std::string& unit, double depth_clearance,
                  const std::map<std::string, std::vector<std::pair<double, double>>>& data) {
  Chart c = bench::make_chart(what + " sent to the user against insertion depth, trial 0 at clearance " +
                                  bench::fixed(depth_clearance, 2) + " mm (depth 0: the peg's tip at the hole's entry)",
                              "depth (mm)", what + " (" + unit + ")");
  for (const auto& [name, points] : data) {
    Series s;
    s.label = name;
    s.style = Series::Style::points;
    for (const auto& [x, y] : points) s.x.push_back(x), s.y.push_back(y);
    c.series.push_back(s);
  }
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_assembly", [&] {
    const Options o = parse_options(argc, argv);
    const std::vector<BenchMethod> methods = methods_from(o.methods, o.voxels);
    const bool need_device =
        std::any_of(methods.begin(), methods.end(), [](const BenchMethod& m) { return !m.voxel_based(); });
    const std::vector<Cell> cells = make_cells(o);

    std::optional<ComputeContext> ctx;
    std::optional<FftLibrary> fft;
    std::string device_name = "host only";
    if (need_device) {
      const Device device = bench::loop_device(o.device_spec);  // as `snapfit run` picks it
      device_name = device.info.name;
      std::cout << "device " << describe_device(device.info) << "\n";
      ctx.emplace(make_compute_context(device));
      fft.emplace();
    }
    const std::string load_start = bench::read_loadavg();
    fs::create_directories(o.out_dir);
    TrialFiles out{
        {fs::path(o.out_dir) / "trials.csv",
         "pair,method,clearance,trial,success,inserted,position_error,lateral_error,axial_error,angle_error,"
         "max_penetration,max_force_step,force_hf_rms,peak_force,frame_p99_ms,frame_wall_p99_ms,misses,"
         "frames,lateral_offset,tilt_deg,approach_offset,duration_s"},
        {fs::path(o.out_dir) / "wrench_vs_depth.csv", "pair,method,clearance,trial,time_s,depth,force_n,torque_nm"},
        o.clearances.size() > 1 ? o.clearances[o.clearances.size() / 2] : o.clearances[0],
        {},
        {}};
    std::vector<Summary> summaries;
    const auto started = std::chrono::steady_clock::now();
    for (const Cell& cell : cells) {
      std::cout << "== " << cell.scene.name << "\n";
      const AssemblyPair parts = prepare_assembly_pair(cell.scene);
      const MeshDistanceIndex i1(parts.part(1).mesh), i2(parts.part(2).mesh);
      for (const BenchMethod& method : methods)
        summaries.push_back(run_method(o, out, cell, method, parts, i1, i2, ctx, fft));
    }
    const double seconds = seconds_since(started);
    const std::string load_end = bench::read_loadavg();

    // The summary per cell: success rate, medians of the errors, the worst penetration.
    std::ostringstream md;
    bench::CsvFile scsv(fs::path(o.out_dir) / "summary.csv",
                        "pair,method,clearance,trials,success_rate,inserted_rate,median_position_error,"
                        "median_angle_error,median_max_penetration,max_penetration,median_max_force_step,"
                        "median_force_hf_rms,frame_p99_ms,frame_wall_p99_ms,misses");
    md << "| pair | method | clearance (mm) | trials | success | inserted | position error (mm, median) | angle "
          "error (deg, median) | max penetration (mm, median / max) | max force step (N, median) | query CPU "
          "p99 (ms, max) | misses |\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    nlohmann::json cells_json = nlohmann::json::array();
    std::map<std::string, Series> success_series;
    for (const Summary& s : summaries) cells_json.push_back(summarise(s, scsv, md, success_series));
    std::cout << "\n"
              << md.str() << "\n"
              << summaries.size() << " cells x methods, " << o.trials << " trials each, in " << bench::fixed(seconds, 0)
              << " s; load average " << load_start << " -> " << load_end << "\n";
    std::ofstream(fs::path(o.out_dir) / "summary.md") << md.str();

    Chart success = bench::make_chart("Imprecise-user insertions of the peg: success rate against clearance (" +
                                          std::to_string(o.trials) + " trials per point; clearance 0 drawn at 0.01 mm)",
                                      "clearance (mm)", "success (%)", true);
    for (auto& [name, series] : success_series) success.series.push_back(series);
    success.y_min = 0, success.y_max = 100;
    const std::vector<Chart> charts = {success, depth_chart("|force|", "N", out.depth_clearance, out.force_depth),
                                       depth_chart("|torque|", "N m", out.depth_clearance, out.torque_depth)};
    nlohmann::json report = bench::run_record(argc, argv, device_name, load_start);
    report.update({{"trials", o.trials},
                   {"seed", o.seed},
                   {"modes", o.modes},
                   {"penetration_stride", o.stride},
                   {"seconds", seconds},
                   {"cells", cells_json}});
    bench::write_json(fs::path(o.out_dir) / "summary.json", report);
    const std::string page = bench::write_charts(o.out_dir, "bench_assembly: imprecise-user insertions",
                                                 bench::command_line(argc, argv), charts);
    std::cout << "wrote " << o.out_dir << "/trials.csv, summary.csv, summary.md, summary.json, wrench_vs_depth.csv and "
              << page << "\n";
    return 0;
  });
}
