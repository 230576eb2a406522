// snapfit against exact mesh collision (FCL, Debian libfcl-dev) on the same part pair
// at the same poses: query time against triangle count, and how often snapfit's
// collision verdict agrees with FCL's, against m'.
//
//   bench_peers --help lists its options.
//
// Part pair: the scene's two parts (default scenes/default.json: the peg and the hole
// block, zero clearance, built by the pipeline, pipeline/assembly_pair.h), then refined by
// longest-edge bisection (mesh/triangle_refine.h; the surface and its orientation are
// unchanged, only the triangles get smaller) to about 1e3 (the scene's own meshes when
// they have about that many), 1e4, 1e5 and 1e6 triangles for both parts together
// (--quick: 1e3 and 1e4). One radius for both parts, adjusted until the count is within
// 30% of the target.
// Poses: N (default 400, --quick 60) times evenly spread over the scene's trajectory
// (scheduler/haptics/trajectory.h), each perturbed by up to +-0.5 (scene units) per axis and up
// to 2 degrees about a random axis (seeded); poses that snapfit flags as outside its
// padded box are dropped for both. Part 2's pose is relative to part 1 (part 1 at the
// identity), as in include/snapfit/query.h: x -> R x + t.
// Per triangle count:
//   FCL     BVHModel<OBBRSSd> build time per part (beginModel/addSubModel/endModel);
//           fcl::collide (1 contact, no contact data) and fcl::distance (exact: rel_err =
//           abs_err = 0, no nearest points) per pose, wall clock of one call after setting
//           part 2's transform; p50 / p99 over the poses. Distance queries stop after a time
//           budget per level (30 s, --quick 3 s); the count done is reported.
//   snapfit the pipeline's stages (pipeline/assembly_pair.h) on the indicator version of
//           the scene (descriptor kind "indicator", as scenes/collision_only.json; 6-DOF
//           with energy, force and torque, so torque spectra too), refined levels with
//           their meshes put in place of the scene's after stage 1. Precompute time
//           (fields, from the field cache when present: flagged; --no-cache recomputes)
//           and spectra time. Then QueryEngine per-query latency, each pose once after 20 warm-up
//           queries, p50 / p99, at m' = 4096 and 32768, for the default scene's variant
//           (6-DOF energy + force + torque, tricubic) and for the verdict variant (6-DOF
//           energy + force, tricubic). The grid, and so the query cost, depends on the
//           scene's spacing and the parts' boxes only, not on the triangles.
// Collision verdict: with indicator fields the affinities are i*w1 and i*w2, so
// f = -integral w1 w2 dV and the energy E = -Re f is the overlap volume (scene units^3),
// low-passed to the m' retained modes. snapfit says "collision" when E > tau; tau =
// 0.5 h^3 (half a grid cell, h the grid spacing): the sampled indicators cannot resolve
// an overlap smaller than the volume one grid point stands for. Agreement with
// fcl::collide at m' = 1024 .. 32768 per level, with the confusion counts, and a sweep of
// tau in {0.1, 0.25, ..., 64} h^3 at every m' (the truncated overlap rings: free poses get
// |E| well above half a cell at small m'), with the tau that agrees best per m'.
// --quick doubles the grid spacing (8x fewer grid points, so a cold run stays near a minute):
// its figures are not the default scene's.
// Output in DIR (default results/bench_peers): peers.csv (per level), agreement.csv (per
// level, m' and tau), poses.csv (per pose at the first level: pose, FCL verdict and
// distance, snapfit energy per m'), peers.json (everything, with device, load averages,
// command line, date) and charts.html (query time log-log, build time, agreement).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/progress.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/compute_context.h"
#include "engine/spectra/fft3d.h"
#include "mesh/triangle_refine.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/bench_poses.h"
#include "perf/fcl_peer.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/error.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace {

using namespace snapfit::bench;  // perf/*.h: tables, contention, poses, FCL
using Clock = std::chrono::steady_clock;
using snapfit::Mesh;
using snapfit::Pose;
using snapfit::QueryEngine;
using snapfit::QueryVariant;

// ---------------------------------------------------------------- command line

struct Args : CommonArgs {
  bool use_cache = true;
  std::string scene = "scenes/default.json";
  int poses = 0;  // 0: 400, or 60 with --quick
};

Args parse_args(int argc, char** argv) {
  Args a;
  a.out = "results/bench_peers";
  a.command_line = command_line(argc, argv);
  bool no_cache = false;
  CLI::App app{
      "snapfit against exact mesh collision (FCL) on the same part pair at the same poses: query time against "
      "triangle count, and agreement of the collision verdicts against m'",
      "bench_peers"};
  add_common_options(app, a.quick, a.device, a.out,
                     "1e3 and 1e4 triangles, 60 poses, 3 m' values, grid spacing doubled (about a minute)");
  app.add_option("--scene", a.scene, "scene")->check(non_empty());
  app.add_option("--poses", a.poses, "poses along the trajectory (0: 400, --quick 60)")->check(CLI::Range(2, 1000000));
  app.add_flag("--no-cache", no_cache, "recompute the descriptor fields (cold precompute times)");
  parse(app, argc, argv);
  a.use_cache = !no_cache;
  return a;
}

// ---------------------------------------------------------------- refinement

double surface_area(const Mesh& m) {
  double a = 0;
  for (const auto& t : m.triangles)
    a += 0.5 * (m.vertices[t[1]] - m.vertices[t[0]]).cross(m.vertices[t[2]] - m.vertices[t[0]]).norm();
  return a;
}

struct Level {
  std::string label;       // "1e3" ...
  std::size_t target = 0;  // triangles of both parts together
  Mesh part1, part2;
  double radius = 0;  // refinement radius (0: the scene's meshes)
  double refine_s = 0;
  std::size_t triangles() const { return part1.triangles.size() + part2.triangles.size(); }
};

Level make_level(const snapfit::PreparedParts& parts, std::size_t target, const std::string& label) {
  Level L;
  L.label = label;
  L.target = target;
  const std::size_t base = parts.part1.mesh.triangles.size() + parts.part2.mesh.triangles.size();
  const auto t0 = Clock::now();
  if (double(base) >= 0.7 * double(target)) {  // the scene's own meshes are close enough (or finer)
    L.part1 = parts.part1.mesh;
    L.part2 = parts.part2.mesh;
  } else {
    const double area = surface_area(parts.part1.mesh) + surface_area(parts.part2.mesh);
    double r = std::sqrt(area / double(target));  // a piece within radius r has area ~ r^2
    for (int it = 0; it < 8; ++it) {
      L.part1 = snapfit::refine_triangles(parts.part1.mesh, r, 40000000);
      L.part2 = snapfit::refine_triangles(parts.part2.mesh, r, 40000000);
      L.radius = r;
      const double ratio = double(L.triangles()) / double(target);
      if (ratio > 1.0 / 1.3 && ratio < 1.3) break;
      r *= std::sqrt(ratio) * (ratio > 1 ? 1.03 : 0.97);  // count ~ 1 / r^2; nudge past bisection steps
    }
  }
  L.refine_s = seconds_since(t0);
  return L;
}

// ---------------------------------------------------------------- per level results

struct Stat {
  double p50 = std::numeric_limits<double>::quiet_NaN(), p99 = p50, max = p50;
  std::size_t n = 0;
};
Stat stat_us(const std::vector<double>& s) {
  Stat r;
  std::vector<double> us;
  for (double v : s) us.push_back(v * 1e6);
  r.n = us.size();
  if (us.empty()) return r;
  r.p50 = percentile(us, 0.5);
  r.p99 = percentile(us, 0.99);
  r.max = *std::max_element(us.begin(), us.end());
  return r;
}

// p50_us, p99_us, max_us (null when not run) and n.
nlohmann::json stat_json(const Stat& s) {
  return {{"p50_us", num(s.p50)}, {"p99_us", num(s.p99)}, {"max_us", num(s.max)}, {"n", s.n}};
}

struct SnapLatency {
  std::string variant;  // eft_tricubic | ef_tricubic
  std::size_t modes = 0;
  Stat stat;
};

struct LevelResult {
  std::string label;
  std::size_t target = 0, tri1 = 0, tri2 = 0;
  double radius = 0, refine_s = 0;
  double fcl_build1_s = 0, fcl_build2_s = 0;
  Stat collide, distance;
  std::size_t distance_skipped = 0;
  std::vector<int> fcl_collides;     // per pose
  std::vector<double> fcl_distance;  // per pose (NaN: not run)
  double fields_s = 0, spectra_s = 0;
  bool fields_cached = false;
  std::array<std::size_t, 3> fft_dims{};
  std::vector<SnapLatency> snap;
  std::map<std::size_t, std::vector<double>> energy;  // verdict variant, per m', per pose
  double other_cores_fcl = 0, other_cores_snap = 0;
  double load_before = 0, load_after = 0;
  // snapfit's latency of `variant` at m' (nullptr: not timed).
  const Stat* snap_stat(const std::string& variant, std::size_t m) const {
    for (const auto& s : snap)
      if (s.variant == variant && s.modes == m) return &s.stat;
    return nullptr;
  }
};

struct AgreementRow {
  std::string level;
  std::size_t triangles = 0, modes = 0;
  double tau_voxels = 0, tau = 0;
  std::size_t agree = 0, both_collide = 0, both_free = 0, snap_only = 0, fcl_only = 0, poses = 0;
  std::size_t snap_only_within_h = 0;  // of snap_only: FCL distance known and at most one grid spacing
  double fraction() const { return poses ? double(agree) / double(poses) : 0.0; }
};

// ---------------------------------------------------------------- the run

// The sweep: triangle counts, poses, the m' timed and judged, the verdict's thresholds.
struct Plan {
  std::vector<std::pair<std::string, std::size_t>> targets;  // label, triangles of both parts
  std::size_t pose_count = 0;
  std::vector<std::size_t> timing_modes = {4096, 32768}, verdict_modes;
  std::vector<double> tau_voxels = {0.1, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0, 64.0};
  double tau_main = 0.5;
  double distance_budget_s = 0;  // FCL's distance queries per level stop after this
  int warmup = 20;
};

Plan plan_for(const Args& args) {
  Plan p;
  p.targets = args.quick ? std::vector<std::pair<std::string, std::size_t>>{{"1e3", 1000}, {"1e4", 10000}}
                         : std::vector<std::pair<std::string, std::size_t>>{
                               {"1e3", 1000}, {"1e4", 10000}, {"1e5", 100000}, {"1e6", 1000000}};
  p.pose_count = args.poses > 0 ? std::size_t(args.poses) : (args.quick ? 60 : 400);
  p.verdict_modes = args.quick ? std::vector<std::size_t>{1024, 4096, 32768}
                               : std::vector<std::size_t>{1024, 2048, 4096, 8192, 16384, 32768};
  p.distance_budget_s = args.quick ? 3.0 : 30.0;
  return p;
}

// What the levels share: the sweep, the device, the indicator scene and its poses (those
// snapfit accepts, chosen at the first level).
struct Peers {
  const Args& args;
  Plan plan;
  const snapfit::FftLibrary& fft;
  const snapfit::ComputeContext& ctx;
  const snapfit::Scene& scene;
  snapfit::PairOptions popt;
  std::vector<Pose> all_poses, poses;
  std::size_t dropped = 0;

  Peers(const Args& a, const snapfit::FftLibrary& f, const snapfit::ComputeContext& c, const snapfit::Scene& s)
      : args(a), plan(plan_for(a)), fft(f), ctx(c), scene(s) {}
};

const QueryVariant kEft{true, true, false, snapfit::Interpolation::tricubic};  // the default scene's variant
const QueryVariant kEf{true, false, false, snapfit::Interpolation::tricubic};  // the verdict's

// The scene with the indicator descriptor (scenes/collision_only.json style), 6-DOF; with
// --quick a grid twice as coarse.
snapfit::Scene peers_scene(const snapfit::Scene& base_scene, bool quick) {
  snapfit::Scene scene = snapfit::indicator_scene(base_scene);
  scene.name = base_scene.name + " (indicator)";
  scene.motion = snapfit::Motion::six_dof;
  scene.outputs = snapfit::Outputs{true, true, true};
  if (quick) {  // CI proves the program runs: a grid twice as coarse (8x fewer points) keeps it short
    if (scene.grid.spacing) scene.grid.spacing = 2.0 * *scene.grid.spacing;
    if (scene.grid.resolution) scene.grid.resolution = std::max(8, *scene.grid.resolution / 2);
    std::cout << "  --quick: grid spacing doubled (figures are not the default scene's)\n";
  }
  return scene;
}

// snapfit's precompute at the level: the pipeline's stages with the level's meshes in
// place of the scene's (the same surface split finer: the same boxes, so the same grids).
snapfit::PairSpectra precompute(Peers& b, const Level& L, LevelResult& R) {
  const auto t0 = Clock::now();
  snapfit::AssemblyPair pair = snapfit::prepare_assembly_pair(b.scene);
  if (L.radius > 0) {
    pair.parts.part1.mesh = L.part1;
    pair.parts.part2.mesh = L.part2;
  }
  snapfit::compute_assembly_fields(pair, b.ctx, b.popt);
  R.fields_cached = pair.fields1.from_cache && pair.fields2.from_cache;
  R.fields_s = seconds_since(t0);
  const auto t1 = Clock::now();
  snapfit::compute_assembly_spectra(pair, b.ctx, b.fft, b.popt);
  R.spectra_s = pair.spectra_from_cache ? 0.0 : seconds_since(t1);
  return std::move(pair.spectra);
}

// At the first level: the poses snapfit accepts (inside its padded box).
void select_poses(Peers& b, QueryEngine& engine_ef) {
  engine_ef.set_modes(1024);
  b.poses = usable_poses(engine_ef, b.all_poses, b.dropped);
  if (b.poses.empty()) throw snapfit::Error("no pose inside snapfit's padded box");
  std::cout << "  poses: " << b.poses.size() << " (" << b.dropped << " of " << b.all_poses.size()
            << " outside snapfit's padded box dropped)\n";
}

// snapfit's query time per pose at each timed m' (E+F+T and E+F), and the verdict
// variant's energies at each judged m'.
void time_snapfit(Peers& b, QueryEngine& engine_eft, QueryEngine& engine_ef, LevelResult& R) {
  const std::vector<Pose>& poses = b.poses;
  double sink = 0;
  for (std::size_t m : b.plan.timing_modes)
    for (QueryEngine* e : {&engine_eft, &engine_ef}) {
      e->set_modes(m);
      for (int i = 0; i < b.plan.warmup; ++i) sink += e->query(poses[std::size_t(i) % poses.size()]).energy;
      std::vector<double> s;
      for (const Pose& p : poses) {
        const auto t = Clock::now();
        const auto q = e->query(p);
        s.push_back(seconds_since(t));
        sink += q.energy;
      }
      R.snap.push_back({e == &engine_eft ? "eft_tricubic" : "ef_tricubic", e->modes(), stat_us(s)});
    }
  for (std::size_t m : b.plan.verdict_modes) {
    engine_ef.set_modes(m);
    std::vector<double> E;
    for (const auto& q : engine_ef.query_batch(poses)) E.push_back(q.flags == snapfit::query_ok ? q.energy : NAN);
    R.energy[m] = E;
  }
  if (sink == 12345.678) std::cout << "";
}

// FCL at the level: BVH build, collide at every pose, distance within the time budget.
void run_fcl(Peers& b, const Level& L, LevelResult& R) {
  const std::vector<Pose>& poses = b.poses;
  auto m1 = fcl_model(L.part1, R.fcl_build1_s);
  auto m2 = fcl_model(L.part2, R.fcl_build2_s);
  std::cout << "  FCL BVH build (OBBRSS): " << fixed(R.fcl_build1_s, 2) << " s + " << fixed(R.fcl_build2_s, 2) << " s\n"
            << std::flush;
  fcl::CollisionObjectd o1(m1, fcl::Transform3d::Identity()), o2(m2, fcl::Transform3d::Identity());
  {
    fcl::CollisionRequestd req(1, false);
    std::vector<double> s;
    for (const Pose& p : poses) {
      const auto t = Clock::now();
      o2.setTransform(fcl_transform(p));
      o2.computeAABB();
      fcl::CollisionResultd res;
      fcl::collide(&o1, &o2, req, res);
      s.push_back(seconds_since(t));
      R.fcl_collides.push_back(res.isCollision() ? 1 : 0);
    }
    R.collide = stat_us(s);
  }
  {
    fcl::DistanceRequestd req;
    req.enable_nearest_points = false;
    req.rel_err = 0;
    req.abs_err = 0;
    std::vector<double> s;
    const auto t_budget = Clock::now();
    R.fcl_distance.assign(poses.size(), NAN);
    for (std::size_t i = 0; i < poses.size(); ++i) {
      if (seconds_since(t_budget) > b.plan.distance_budget_s) {
        R.distance_skipped = poses.size() - i;
        break;
      }
      const auto t = Clock::now();
      o2.setTransform(fcl_transform(poses[i]));
      o2.computeAABB();
      fcl::DistanceResultd res;
      fcl::distance(&o1, &o2, req, res);
      s.push_back(seconds_since(t));
      R.fcl_distance[i] = res.min_distance;
    }
    R.distance = stat_us(s);
  }
}

LevelResult measure_level(Peers& b, const snapfit::PreparedParts& parts, const std::string& label, std::size_t target,
                          double& spacing) {
  LevelResult R;
  R.label = label;
  R.target = target;
  std::cout << "\n[level " << label << "] refining..." << std::flush;
  Level L = make_level(parts, target, label);
  R.tri1 = L.part1.triangles.size();
  R.tri2 = L.part2.triangles.size();
  R.radius = L.radius;
  R.refine_s = L.refine_s;
  std::cout << " " << R.tri1 << " + " << R.tri2 << " = " << L.triangles() << " triangles"
            << (L.radius > 0 ? " (split to radius " + fixed(L.radius, 3) + ", " + fixed(L.refine_s, 1) + " s)"
                             : " (the scene's meshes)")
            << "\n";
  R.load_before = load1();

  const auto cs0 = cpu_sample();
  const snapfit::PairSpectra spectra = precompute(b, L, R);
  R.fft_dims = spectra.dims;
  spacing = spectra.spacing;
  std::cout << "  snapfit precompute: fields " << fixed(R.fields_s, 1) << " s"
            << (R.fields_cached ? " (from the field cache)" : " (computed)") << ", spectra " << fixed(R.spectra_s, 1)
            << " s, FFT grid " << spectra.dims[0] << "x" << spectra.dims[1] << "x" << spectra.dims[2] << ", h "
            << spectra.spacing << "\n"
            << std::flush;
  auto engine_eft = make_query_engine(b.ctx, spectra, kEft);
  auto engine_ef = make_query_engine(b.ctx, spectra, kEf);
  if (b.poses.empty()) select_poses(b, *engine_ef);
  time_snapfit(b, *engine_eft, *engine_ef, R);
  R.other_cores_snap = other_cores(cs0, cpu_sample());
  for (const auto& s : R.snap)
    std::cout << "  snapfit " << padr(s.variant == "eft_tricubic" ? "6-DOF E+F+T tricubic" : "6-DOF E+F tricubic", 21)
              << " m' " << pad(std::to_string(s.modes), 6) << "  p50 " << pad(fixed(s.stat.p50, 1), 8) << " us  p99 "
              << pad(fixed(s.stat.p99, 1), 8) << " us\n";

  const auto cf0 = cpu_sample();
  run_fcl(b, L, R);
  R.other_cores_fcl = other_cores(cf0, cpu_sample());
  R.load_after = load1();
  std::size_t colliding = 0;
  for (int c : R.fcl_collides) colliding += std::size_t(c);
  std::cout << "  FCL collide   p50 " << pad(fixed(R.collide.p50, 1), 10) << " us  p99 "
            << pad(fixed(R.collide.p99, 1), 10) << " us  (" << colliding << " of " << b.poses.size()
            << " poses collide)\n"
            << "  FCL distance  p50 " << pad(fixed(R.distance.p50, 1), 10) << " us  p99 "
            << pad(fixed(R.distance.p99, 1), 10) << " us  (" << R.distance.n << " poses"
            << (R.distance_skipped ? ", " + std::to_string(R.distance_skipped) + " left out by the time budget" : "")
            << ")\n"
            << "  other processes used " << fixed(R.other_cores_snap, 2) << " cores (snapfit part), "
            << fixed(R.other_cores_fcl, 2) << " cores (FCL part)\n"
            << std::flush;
  return R;
}

// snapfit's verdict (E > tau) against FCL's per level, m' and tau.
std::vector<AgreementRow> agreement_rows(const std::vector<LevelResult>& levels, const Plan& plan, double spacing) {
  const double voxel = spacing * spacing * spacing;
  std::vector<AgreementRow> agreement;
  for (const auto& R : levels)
    for (std::size_t m : plan.verdict_modes)
      for (double tv : plan.tau_voxels) {
        AgreementRow a;
        a.level = R.label;
        a.triangles = R.tri1 + R.tri2;
        a.modes = m;
        a.tau_voxels = tv;
        a.tau = tv * voxel;
        const auto& E = R.energy.at(m);
        for (std::size_t i = 0; i < E.size(); ++i) {
          if (!std::isfinite(E[i])) continue;
          const bool s = E[i] > a.tau, f = R.fcl_collides[i] != 0;
          ++a.poses;
          if (s == f) ++a.agree;
          if (s && f) ++a.both_collide;
          if (!s && !f) ++a.both_free;
          if (s && !f) ++a.snap_only;
          if (s && !f && std::isfinite(R.fcl_distance[i]) && R.fcl_distance[i] <= spacing) ++a.snap_only_within_h;
          if (!s && f) ++a.fcl_only;
        }
        agreement.push_back(a);
      }
  return agreement;
}

void print_times(const std::vector<LevelResult>& levels) {
  std::cout << "\nquery time per pose (us), p50 / p99; FCL BVH build and snapfit precompute (s)\n";
  std::cout << "  " << padr("triangles", 10) << pad("FCL build", 10) << pad("collide", 20) << pad("distance", 22)
            << pad("snap m'4096", 18) << pad("snap m'32768", 18) << pad("snap pre", 10) << "\n";
  for (const auto& R : levels) {
    const Stat *a = R.snap_stat("eft_tricubic", 4096), *b = R.snap_stat("eft_tricubic", 32768);
    std::cout << "  " << padr(std::to_string(R.tri1 + R.tri2), 10) << pad(fixed(R.fcl_build1_s + R.fcl_build2_s, 2), 10)
              << pad(fixed(R.collide.p50, 1) + " / " + fixed(R.collide.p99, 1), 20)
              << pad(fixed(R.distance.p50, 1) + " / " + fixed(R.distance.p99, 1), 22)
              << pad(a ? fixed(a->p50, 0) + " / " + fixed(a->p99, 0) : "-", 18)
              << pad(b ? fixed(b->p50, 0) + " / " + fixed(b->p99, 0) : "-", 18)
              << pad(fixed(R.fields_s + R.spectra_s, 1) + (R.fields_cached ? "c" : ""), 10) << "\n";
  }
  std::cout << "  (snapfit: 6-DOF E+F+T tricubic, the default scene's variant; 'c': fields from the cache)\n";
}

void print_agreement(const std::vector<LevelResult>& levels, const std::vector<AgreementRow>& agreement,
                     const Plan& plan, double spacing, std::size_t fcl_changes) {
  const double voxel = spacing * spacing * spacing;
  const double tau_main = plan.tau_main;
  std::cout << "\nverdict agreement with fcl::collide, tau = " << tau_main << " h^3 = " << fixed(tau_main * voxel, 4)
            << " (h = " << spacing << "), per m' [both collide / both free / snapfit only / FCL only]\n";
  for (const auto& a : agreement)
    if (a.tau_voxels == tau_main)
      std::cout << "  " << padr(a.level, 5) << " m' " << pad(std::to_string(a.modes), 6) << "  "
                << pad(fixed(100.0 * a.fraction(), 1), 6) << " %  [" << a.both_collide << " / " << a.both_free << " / "
                << a.snap_only << " / " << a.fcl_only << "] of " << a.poses
                << "; snapfit-only with FCL distance <= h: " << a.snap_only_within_h << "\n";
  std::cout << "  best tau of the sweep per m' (first level):";
  for (std::size_t m : plan.verdict_modes) {
    const AgreementRow* best = nullptr;
    for (const auto& a : agreement)
      if (a.level == levels.front().label && a.modes == m && (!best || a.agree > best->agree)) best = &a;
    if (best)
      std::cout << "  m' " << m << ": " << best->tau_voxels << " h^3 -> " << fixed(100.0 * best->fraction(), 1)
                << " %;";
  }
  std::cout << "\n  FCL verdict changes across refinement levels: " << fcl_changes << "\n";
}

void write_csvs(const std::filesystem::path& dir, const std::vector<LevelResult>& levels,
                const std::vector<AgreementRow>& agreement, const std::vector<Pose>& poses, const Plan& plan) {
  const auto& timing_modes = plan.timing_modes;
  const auto& verdict_modes = plan.verdict_modes;
  CsvFile pc(dir / "peers.csv",
             "level,triangles,triangles_part1,triangles_part2,refine_radius,refine_s,fcl_build_s,fcl_build_part1_s,"
             "fcl_build_part2_s,fcl_collide_p50_us,fcl_collide_p99_us,fcl_collide_n,fcl_distance_p50_us,"
             "fcl_distance_p99_us,fcl_distance_n,fcl_distance_skipped,snap_fields_s,snap_fields_cached,snap_spectra_s,"
             "snap_eft_4096_p50_us,snap_eft_4096_p99_us,snap_eft_32768_p50_us,snap_eft_32768_p99_us,"
             "snap_ef_4096_p50_us,snap_ef_4096_p99_us,snap_ef_32768_p50_us,snap_ef_32768_p99_us,other_cores_snap,"
             "other_cores_fcl,load_before,load_after");
  for (const auto& R : levels) {
    std::ostringstream snap;  // the spectra's seconds, then p50 and p99 per variant and m' as the header has them
    snap << R.spectra_s;
    for (const std::string v : {"eft_tricubic", "ef_tricubic"})
      for (std::size_t m : timing_modes)
        if (const Stat* s = R.snap_stat(v, m)) snap << ',' << s->p50 << ',' << s->p99;
    pc.row(R.label, R.tri1 + R.tri2, R.tri1, R.tri2, R.radius, R.refine_s, R.fcl_build1_s + R.fcl_build2_s,
           R.fcl_build1_s, R.fcl_build2_s, R.collide.p50, R.collide.p99, R.collide.n, R.distance.p50, R.distance.p99,
           R.distance.n, R.distance_skipped, R.fields_s, R.fields_cached, snap.str(), R.other_cores_snap,
           R.other_cores_fcl, R.load_before, R.load_after);
  }
  CsvFile ag(dir / "agreement.csv",
             "level,triangles,modes,tau_voxels,tau,poses,agree,fraction,both_collide,both_free,snapfit_only,fcl_only,"
             "snapfit_only_fcl_distance_within_h");
  for (const auto& a : agreement)
    ag.row(a.level, a.triangles, a.modes, a.tau_voxels, a.tau, a.poses, a.agree, a.fraction(), a.both_collide,
           a.both_free, a.snap_only, a.fcl_only, a.snap_only_within_h);
  {
    std::ofstream f(dir / "poses.csv");
    f << "index,tx,ty,tz,qw,qx,qy,qz,fcl_collide,fcl_distance";
    for (std::size_t m : verdict_modes) f << ",energy_m" << m;
    f << "\n";
    const auto& R = levels.front();
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const auto& p = poses[i];
      f << i << ',' << p.translation.x() << ',' << p.translation.y() << ',' << p.translation.z() << ','
        << p.rotation.w() << ',' << p.rotation.x() << ',' << p.rotation.y() << ',' << p.rotation.z() << ','
        << R.fcl_collides[i] << ',' << finite_or_empty(R.fcl_distance[i]);
      for (std::size_t m : verdict_modes) f << ',' << R.energy.at(m)[i];
      f << "\n";
    }
    if (!f) throw snapfit::Error((dir / "poses.csv").string() + ": cannot write");
  }
}

nlohmann::json level_json(const LevelResult& R) {
  nlohmann::json distance = stat_json(R.distance);
  distance["skipped_by_budget"] = R.distance_skipped;
  nlohmann::json sj = nlohmann::json::array();
  for (const auto& s : R.snap) {
    sj.push_back(stat_json(s.stat));
    sj.back().update({{"variant", s.variant}, {"modes", s.modes}});
  }
  return {{"level", R.label},
          {"target", R.target},
          {"triangles", R.tri1 + R.tri2},
          {"triangles_part1", R.tri1},
          {"triangles_part2", R.tri2},
          {"refine_radius", R.radius},
          {"refine_s", R.refine_s},
          {"fcl_build_s", {R.fcl_build1_s, R.fcl_build2_s}},
          {"fcl_collide", stat_json(R.collide)},
          {"fcl_distance", distance},
          {"snapfit_fields_s", R.fields_s},
          {"snapfit_fields_cached", R.fields_cached},
          {"snapfit_spectra_s", R.spectra_s},
          {"fft_dims", R.fft_dims},
          {"snapfit_latency", sj},
          {"other_cores_snap", R.other_cores_snap},
          {"other_cores_fcl", R.other_cores_fcl},
          {"load_before", R.load_before},
          {"load_after", R.load_after}};
}

nlohmann::json agreement_json(const AgreementRow& a) {
  return {{"level", a.level},
          {"triangles", a.triangles},
          {"modes", a.modes},
          {"tau_voxels", a.tau_voxels},
          {"tau", a.tau},
          {"poses", a.poses},
          {"agree", a.agree},
          {"fraction", a.fraction()},
          {"both_collide", a.both_collide},
          {"both_free", a.both_free},
          {"snapfit_only", a.snap_only},
          {"fcl_only", a.fcl_only},
          {"snapfit_only_fcl_distance_within_h", a.snap_only_within_h}};
}

// The run as a whole (perf/bench_common.h), the scene's name and spacing.
struct RunRecord : RunSpan {
  std::string base_scene_name;
  double spacing = 0;
};

nlohmann::json report_json(const Peers& b, const RunRecord& run, const std::vector<LevelResult>& levels,
                           const std::vector<AgreementRow>& agreement, std::size_t fcl_changes) {
  nlohmann::json j = run.header("bench_peers", b.args.command_line, b.args.quick, b.ctx.device.info);
  j["other_cores_run"] = run.others_run;
  j["scene"] = {{"file", b.args.scene},
                {"name", run.base_scene_name},
                {"descriptor_used", "indicator (winding number), as scenes/collision_only.json"},
                {"spacing", run.spacing},
                {"units", b.scene.units}};
  j["poses"] = {{"requested", b.all_poses.size()},
                {"used", b.poses.size()},
                {"dropped_outside_grid", b.dropped},
                {"perturbation", "+-0.5 scene units per axis, up to 2 degrees about a random axis, seed 20261122"}};
  j["verdict"] = {{"rule", "collision when E > tau; E = overlap volume of the two indicators, low-passed to m' modes"},
                  {"tau_main_voxels", b.plan.tau_main},
                  {"tau_main", b.plan.tau_main * run.spacing * run.spacing * run.spacing},
                  {"why",
                   "half a grid cell: the sampled indicators cannot resolve an overlap smaller than the volume "
                   "one grid point stands for"}};
  j["method"] = {
      {"fcl",
       "BVHModel<OBBRSSd>; collide with 1 contact and no contact data; distance exact (rel_err = abs_err = 0); "
       "wall clock of setTransform + computeAABB + the call, one call per pose"},
      {"snapfit", "QueryEngine::query wall clock, one call per pose after " + std::to_string(b.plan.warmup) +
                      " warm-up; fields + spectra as build_assembly_pair does on the indicator scene"}};
  j["levels"] = nlohmann::json::array();
  for (const auto& R : levels) j["levels"].push_back(level_json(R));
  j["agreement"] = nlohmann::json::array();
  for (const auto& a : agreement) j["agreement"].push_back(agreement_json(a));
  j["fcl_verdict_changes_across_levels"] = fcl_changes;
  return j;
}

std::vector<snapfit::Chart> charts(const std::vector<LevelResult>& levels, const std::vector<AgreementRow>& agreement,
                                   const Plan& plan) {
  std::vector<snapfit::Chart> charts;
  {
    snapfit::Chart c = make_chart("query time vs triangles: FCL vs snapfit (same poses)", "triangles (both parts)",
                                  "time per query (us)", true, true);
    auto add = [&](const std::string& label, auto get) {
      snapfit::Series s;
      s.label = label;
      for (const auto& R : levels) s.x.push_back(double(R.tri1 + R.tri2)), s.y.push_back(get(R));
      c.series.push_back(s);
    };
    add("FCL collide p50", [](const LevelResult& R) { return R.collide.p50; });
    add("FCL collide p99", [](const LevelResult& R) { return R.collide.p99; });
    add("FCL distance p50", [](const LevelResult& R) { return R.distance.p50; });
    add("FCL distance p99", [](const LevelResult& R) { return R.distance.p99; });
    for (std::size_t m : plan.timing_modes)
      for (const bool p99 : {false, true})
        add("snapfit E+F+T m' " + std::to_string(m) + (p99 ? " p99" : " p50"), [&](const LevelResult& R) {
          const Stat* s = R.snap_stat("eft_tricubic", m);
          return s ? (p99 ? s->p99 : s->p50) : std::numeric_limits<double>::quiet_NaN();
        });
    c.hlines.push_back({1000.0, "1 ms"});
    charts.push_back(c);
  }
  {
    snapfit::Chart c = make_chart("precompute vs triangles: FCL BVH build, snapfit fields + spectra",
                                  "triangles (both parts)", "seconds", true, true);
    snapfit::Series a, b;
    a.label = "FCL BVH build (OBBRSS, both parts)";
    b.label = "snapfit indicator fields + spectra";
    for (const auto& R : levels) {
      a.x.push_back(double(R.tri1 + R.tri2)), a.y.push_back(R.fcl_build1_s + R.fcl_build2_s);
      if (!R.fields_cached) b.x.push_back(double(R.tri1 + R.tri2)), b.y.push_back(R.fields_s + R.spectra_s);
    }
    c.series = {a, b};
    charts.push_back(c);
  }
  {
    snapfit::Chart c = make_chart("collision verdict agreement with FCL vs m' (tau = 0.5 h^3)", "retained modes m'",
                                  "poses where snapfit and FCL agree (%)", true);
    for (const auto& R : levels) {
      snapfit::Series s;
      s.label = R.label + " (" + std::to_string(R.tri1 + R.tri2) + " triangles)";
      for (const auto& a : agreement)
        if (a.level == R.label && a.tau_voxels == plan.tau_main)
          s.x.push_back(double(a.modes)), s.y.push_back(100.0 * a.fraction());
      c.series.push_back(s);
    }
    charts.push_back(c);
  }
  return charts;
}

int run(const Args& args) {
  RunRecord run;
  run.announce("bench_peers", args.command_line);

  const snapfit::FftLibrary fft;
  const snapfit::ComputeContext ctx =
      snapfit::make_compute_context(snapfit::select_device(snapfit::device_spec_from(args.device)));
  const auto& info = ctx.device.info;
  std::cout << "  device: " << snapfit::describe_device(info) << ", driver " << info.driver_version << "\n";
  const snapfit::Scene base_scene = snapfit::load_scene(args.scene);
  run.base_scene_name = base_scene.name;
  const snapfit::Scene scene = peers_scene(base_scene, args.quick);
  const snapfit::PreparedParts parts = snapfit::prepare_assembly_pair(scene).parts;
  std::cout << "  scene " << args.scene << " (" << base_scene.name << "): " << base_scene.part1.name << " "
            << parts.part1.mesh.triangles.size() << " triangles, " << base_scene.part2.name << " "
            << parts.part2.mesh.triangles.size() << " triangles; descriptor switched to the indicator\n";
  if (!(snapfit::query_variant_for(base_scene).torque))
    std::cout << "  note: the scene itself does not ask for torque; E+F+T is timed anyway (the default scene's)\n";

  Peers b(args, fft, ctx, scene);
  b.all_poses = trajectory_poses(scene, b.plan.pose_count, 20261122u, 0.5, 2.0);
  b.popt.use_cache = args.use_cache;
  b.popt.descriptors.progress = snapfit::pass_progress_bars(std::cerr);
  b.popt.note = [](const std::string& m) { std::cerr << "  snapfit: " << m << "\n"; };
  std::vector<LevelResult> levels;
  for (const auto& [label, target] : b.plan.targets)
    levels.push_back(measure_level(b, parts, label, target, run.spacing));

  const std::vector<AgreementRow> agreement = agreement_rows(levels, b.plan, run.spacing);
  // FCL's verdicts should not change with refinement (the surface is the same).
  std::size_t fcl_changes = 0;
  for (std::size_t l = 1; l < levels.size(); ++l)
    for (std::size_t i = 0; i < b.poses.size(); ++i)
      fcl_changes += levels[l].fcl_collides[i] != levels[0].fcl_collides[i];
  print_times(levels);
  print_agreement(levels, agreement, b.plan, run.spacing, fcl_changes);

  run.stop();
  const std::filesystem::path dir(args.out);
  std::filesystem::create_directories(dir);
  write_csvs(dir, levels, agreement, b.poses, b.plan);
  write_json(dir / "peers.json", report_json(b, run, levels, agreement, fcl_changes));
  write_charts(dir, "bench_peers: FCL and snapfit", args.command_line, charts(levels, agreement, b.plan));
  std::cout << run.end_text() << "other processes kept " << fixed(run.others_run, 2) << " cores busy on average\nwrote "
            << (dir / "peers.csv").string() << ", agreement.csv, poses.csv, peers.json, charts.html\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return guarded_main("bench_peers", [&] { return run(parse_args(argc, argv)); });
}
