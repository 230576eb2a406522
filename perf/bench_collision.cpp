// Seed 001's collision predicate (engine/query/collision_predicate.h) against FCL's verdicts on
// the shipped scenes: agreement and per-query time at m' = 512 .. 4,096.
//
//   bench_collision --help lists its options.
//
// Scenes: every scenes/*.json (--quick: collision_only.json and default.json with the grid
// spacing doubled, so its figures are not the scenes' own), each switched to the indicator
// descriptor (pipeline/assembly_pair.h indicator_scene), so a query's energy is the overlap
// volume of the parts truncated to m' modes. Poses per scene: N (default 198, --quick 30),
// a third evenly along the scene's trajectory, a third the same times shifted by up to
// +-0.5 (scene units) per axis and, for 6-DOF scenes, turned by up to 2 degrees, a third
// shifted by up to +-3 and turned by up to 10 degrees (seeded): near contact wherever the
// trajectory is, and some deep. Poses snapfit flags as outside its padded box are
// dropped.
// Reference: fcl::collide on the parts' meshes (OBBRSS BVHs) at the same poses. Distance
// to contact per pose: fcl::distance where FCL says free; where it says collide, minus
// the deepest vertex of one part inside the other (mesh/mesh_distance.h, exact in double;
// 0 when only edges cross).
// Predicates per m': "bound": overlap > B(m'), the Cauchy-Schwarz truncation bound
// (engine/query/collision_predicate.h, derived from the two spectra); "estimate": overlap above
// the query's own error estimate (engine/query/error_estimate.h: the two octave bands below the
// cut, its scale measured against the untruncated sum); "zero": overlap > 0, the seed's
// g > 0 read literally on the truncated sum. True/false positive/negative counts
// against FCL, rates, the largest |distance to contact| among the disagreements, and the
// agreement among the poses farther than 2 h (h the grid spacing) from contact.
// Time: the energy-only query (the scene's motion, tricubic for 6-DOF) of one pose,
// each pose once after 20 warm-up queries, median and p99.
// Output in DIR (default results/bench_collision): collision.csv (per scene, m' and
// predicate), poses.csv (per pose and m'), collision.json, charts.html.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/progress.h"
#include "engine/query/collision_predicate.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "mesh/mesh_distance.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/bench_poses.h"
#include "perf/fcl_peer.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/error.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace {

namespace fs = std::filesystem;
using namespace snapfit;
using namespace snapfit::bench;  // perf/bench_common.h: tables, CSV, JSON
using Clock = std::chrono::steady_clock;

// The deepest vertex of `a` (placed by pose_a) inside `b_index` (b at the identity): >= 0.
double deepest_vertex(const Mesh& a, const Pose& pose_a, const MeshDistanceIndex& b_index) {
  double depth = 0;
  for (const Eigen::Vector3d& v : a.vertices) depth = std::max(depth, -b_index.signed_distance(pose_a.apply(v)));
  return depth;
}

struct Confusion {
  std::size_t tp = 0, fp = 0, fn = 0, tn = 0;
  double worst_fp = 0, worst_fn = 0;   // largest |distance to contact| among false positives / negatives
  std::size_t far = 0, far_agree = 0;  // poses farther than `near` from contact, and those agreeing
  double near = 0;
  void add(bool said, bool truth, double distance) {
    if (std::abs(distance) > near) ++far, far_agree += said == truth;
    if (said && truth) ++tp;
    if (said && !truth) ++fp, worst_fp = std::max(worst_fp, std::abs(distance));
    if (!said && truth) ++fn, worst_fn = std::max(worst_fn, std::abs(distance));
    if (!said && !truth) ++tn;
  }
  void merge(const Confusion& o) {
    tp += o.tp, fp += o.fp, fn += o.fn, tn += o.tn, far += o.far, far_agree += o.far_agree;
    worst_fp = std::max(worst_fp, o.worst_fp), worst_fn = std::max(worst_fn, o.worst_fn);
  }
  double rate(std::size_t n, std::size_t d) const { return d ? double(n) / double(d) : 0.0; }
  double tpr() const { return rate(tp, tp + fn); }  // of FCL's collisions, found
  double fpr() const { return rate(fp, fp + tn); }  // of FCL's free poses, called colliding
  double agreement() const { return rate(tp + tn, tp + fp + fn + tn); }
};

struct Row {
  std::string scene;
  std::size_t modes = 0;
  std::string predicate;
  Confusion c;
  double bound = 0, spacing = 0, p50_us = 0, p99_us = 0;
};

struct Options {
  bool quick = false;
  std::string device, out = "results/bench_collision";
  std::size_t pose_count = 0;
  std::vector<std::string> scene_files;
};

Options parse_options(int argc, char** argv) {
  Options o;
  int pose_arg = 0;
  CLI::App app{
      "Seed 001's collision predicate (truncated overlap above its truncation bound) against fcl::collide "
      "on the shipped scenes, at m' = 512, 1024, 2048, 4096: agreement and query time.",
      "bench_collision"};
  add_common_options(app, o.quick, o.device, o.out, "collision_only.json and default.json (spacing doubled), 30 poses");
  app.add_option("--poses", pose_arg, "poses per scene (0: 198, --quick 30)")->check(CLI::Range(2, 100000));
  app.add_option("--scene", o.scene_files, "scene, repeatable (default: every scenes/*.json)");
  parse(app, argc, argv);
  if (o.scene_files.empty()) {
    if (o.quick) {
      o.scene_files = {"scenes/collision_only.json", "scenes/default.json"};
    } else {
      for (const auto& e : fs::directory_iterator("scenes"))
        if (e.path().extension() == ".json") o.scene_files.push_back(e.path().string());
      std::sort(o.scene_files.begin(), o.scene_files.end());
    }
  }
  o.pose_count = pose_arg > 0 ? std::size_t(pose_arg) : (o.quick ? 30 : 198);
  return o;
}

const std::vector<std::size_t> kModes = {512, 1024, 2048, 4096};

// The scene's poses (see the top of the file) that snapfit does not flag as outside its
// padded box at the first m'.
std::vector<Pose> scene_poses(const Scene& scene, QueryEngine& engine, std::size_t pose_count, double h,
                              const AssemblyPair& pair) {
  const bool rotates = scene.motion == Motion::six_dof;
  std::vector<Pose> candidates = trajectory_poses(scene, pose_count / 3, 20261124u, 0.0, 0.0);
  for (const Pose& p : trajectory_poses(scene, pose_count / 3, 20261125u, 0.5, rotates ? 2.0 : 0.0))
    candidates.push_back(p);
  for (const Pose& p : trajectory_poses(scene, pose_count - 2 * (pose_count / 3), 20261126u, 3.0, rotates ? 10.0 : 0.0))
    candidates.push_back(p);
  if (!rotates)  // part 2's orientation is in its mesh (pipeline/assembly_pair.h)
    for (Pose& p : candidates) p.rotation = Eigen::Quaterniond::Identity();
  engine.set_modes(kModes.front());
  std::size_t rejected = 0;
  const std::vector<Pose> poses = usable_poses(engine, candidates, rejected);
  std::cout << "  FFT grid " << pair.spectra.dims[0] << "x" << pair.spectra.dims[1] << "x" << pair.spectra.dims[2]
            << ", h " << h << "; poses " << poses.size() << " of " << candidates.size() << " inside the padded box\n";
  return poses;
}

// FCL's verdict at each pose and the distance to contact (negative: the depth).
struct Truth {
  std::vector<int> collides;
  std::vector<double> distance;
};
Truth fcl_truth(const AssemblyPair& pair, const std::vector<Pose>& poses) {
  const Mesh& m1 = pair.parts.part1.mesh;
  const Mesh& m2 = pair.parts.part2.mesh;
  double build_s = 0;
  fcl::CollisionObjectd o1(fcl_model(m1, build_s), fcl::Transform3d::Identity());
  fcl::CollisionObjectd o2(fcl_model(m2, build_s), fcl::Transform3d::Identity());
  const MeshDistanceIndex index1(m1), index2(m2);
  Truth t{std::vector<int>(poses.size()), std::vector<double>(poses.size())};
  for (std::size_t i = 0; i < poses.size(); ++i) {
    o2.setTransform(fcl_transform(poses[i]));
    fcl::CollisionRequestd creq(1, false);
    fcl::CollisionResultd cres;
    fcl::collide(&o1, &o2, creq, cres);
    t.collides[i] = cres.isCollision();
    if (t.collides[i]) {
      t.distance[i] = -std::max(deepest_vertex(m2, poses[i], index1), deepest_vertex(m1, poses[i].inverse(), index2));
    } else {
      fcl::DistanceRequestd dreq;
      dreq.rel_err = dreq.abs_err = 0;
      fcl::DistanceResultd dres;
      fcl::distance(&o1, &o2, dreq, dres);
      t.distance[i] = dres.min_distance;
    }
  }
  return t;
}

// The three predicates' verdicts against FCL's at each m', and the query time; each
// pose's overlap into poses.csv.
void measure_modes(const std::string& file, QueryEngine& engine, const TruncationTails& tails, double h,
                   const std::vector<Pose>& poses, const Truth& truth, CsvFile& poses_csv, std::vector<Row>& rows) {
  const int warmup = 20;
  for (std::size_t m : kModes) {
    engine.set_modes(m);
    const std::vector<QueryResult> res = engine.query_batch(poses);
    Row bound_row{file, engine.modes(), "bound", {}, tails.bound(engine.modes()), h};
    Row estimate_row{file, engine.modes(), "estimate", {}, 0.0, h};
    Row zero_row{file, engine.modes(), "zero", {}, 0.0, h};
    bound_row.c.near = estimate_row.c.near = zero_row.c.near = 2 * h;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      const CollisionVerdict v = collision_verdict(res[i], tails);
      bound_row.c.add(v.collides, truth.collides[i] != 0, truth.distance[i]);
      estimate_row.c.add(v.overlap > res[i].error_estimate.energy, truth.collides[i] != 0, truth.distance[i]);
      zero_row.c.add(v.overlap > 0, truth.collides[i] != 0, truth.distance[i]);
      const Pose& p = poses[i];
      poses_csv.row(file, i, p.translation.x(), p.translation.y(), p.translation.z(), p.rotation.w(), p.rotation.x(),
                    p.rotation.y(), p.rotation.z(), truth.collides[i], truth.distance[i], engine.modes(), v.overlap,
                    v.bound);
    }
    // Time: one pose per call, as the haptic frame asks.
    double sink = 0;
    for (int i = 0; i < warmup; ++i) sink += engine.query(poses[std::size_t(i) % poses.size()]).energy;
    std::vector<double> us;
    for (const Pose& p : poses) {
      const auto t0 = Clock::now();
      sink += engine.query(p).energy;
      us.push_back(seconds_since(t0) * 1e6);
    }
    bound_row.p50_us = estimate_row.p50_us = zero_row.p50_us = percentile(us, 0.5);
    bound_row.p99_us = estimate_row.p99_us = zero_row.p99_us = percentile(us, 0.99);
    if (!std::isfinite(sink)) std::cout << "  (non-finite energy)\n";
    for (const Row* r : {&bound_row, &estimate_row, &zero_row})
      std::cout << "  m' " << pad(std::to_string(r->modes), 5) << " " << padr(r->predicate, 8) << " TP/FP/FN/TN "
                << r->c.tp << "/" << r->c.fp << "/" << r->c.fn << "/" << r->c.tn << "  beyond 2h " << r->c.far_agree
                << "/" << r->c.far << "  agreement " << fixed(100 * r->c.agreement(), 1) << "%  worst FP "
                << fixed(r->c.worst_fp, 2) << "  worst FN " << fixed(r->c.worst_fn, 2) << " (h " << h << ")"
                << (r->predicate == "bound" ? "  B " + fixed(r->bound, 3) : "") << "  query p50 " << fixed(r->p50_us, 1)
                << " us p99 " << fixed(r->p99_us, 1) << " us\n";
    rows.push_back(bound_row);
    rows.push_back(estimate_row);
    rows.push_back(zero_row);
  }
}

// Totals over the scenes per m' and predicate; the query times of the slowest scene.
std::vector<Row> totals_of(const std::vector<Row>& rows) {
  std::vector<Row> totals;
  for (std::size_t m : kModes)
    for (const std::string pred : {"bound", "estimate", "zero"}) {
      Row t{"all", m, pred, {}, 0.0, 0.0};
      for (const Row& r : rows)
        if (r.predicate == pred && r.modes == m)
          t.c.merge(r.c), t.p50_us = std::max(t.p50_us, r.p50_us), t.p99_us = std::max(t.p99_us, r.p99_us);
      totals.push_back(t);
    }
  std::cout << "\nall scenes (time: the slowest scene's median / p99)\n";
  for (const Row& t : totals)
    std::cout << "  m' " << pad(std::to_string(t.modes), 5) << " " << padr(t.predicate, 8) << " TPR "
              << fixed(100 * t.c.tpr(), 1) << "%  FPR " << fixed(100 * t.c.fpr(), 1) << "%  agreement "
              << fixed(100 * t.c.agreement(), 1) << "%  (TP/FP/FN/TN " << t.c.tp << "/" << t.c.fp << "/" << t.c.fn
              << "/" << t.c.tn << ")  beyond 2h " << t.c.far_agree << "/" << t.c.far << "  worst FP "
              << fixed(t.c.worst_fp, 2) << ", FN " << fixed(t.c.worst_fn, 2) << "  query p50 " << fixed(t.p50_us, 1)
              << " us, p99 " << fixed(t.p99_us, 1) << " us\n";
  return totals;
}

void write_results(const std::string& out, const std::vector<Row>& rows, const std::vector<Row>& totals,
                   const nlohmann::json& record) {
  CsvFile csv(fs::path(out) / "collision.csv",
              "scene,modes,predicate,tp,fp,fn,tn,tpr,fpr,agreement,beyond_2h,agree_beyond_2h,worst_fp_distance,"
              "worst_fn_distance,bound,spacing,query_p50_us,query_p99_us");
  nlohmann::json jrows = nlohmann::json::array();
  for (const std::vector<Row>* list : {&rows, &totals})
    for (const Row& r : *list) {
      csv.row(r.scene, r.modes, r.predicate, r.c.tp, r.c.fp, r.c.fn, r.c.tn, r.c.tpr(), r.c.fpr(), r.c.agreement(),
              r.c.far, r.c.far_agree, r.c.worst_fp, r.c.worst_fn, r.bound, r.spacing, r.p50_us, r.p99_us);
      jrows.push_back({{"scene", r.scene},
                       {"modes", r.modes},
                       {"predicate", r.predicate},
                       {"tp", r.c.tp},
                       {"fp", r.c.fp},
                       {"fn", r.c.fn},
                       {"tn", r.c.tn},
                       {"beyond_2h", r.c.far},
                       {"agree_beyond_2h", r.c.far_agree},
                       {"worst_fp_distance", r.c.worst_fp},
                       {"worst_fn_distance", r.c.worst_fn},
                       {"bound", r.bound},
                       {"spacing", r.spacing},
                       {"query_p50_us", num(r.p50_us)},
                       {"query_p99_us", num(r.p99_us)}});
    }
  nlohmann::json report = record;
  report["rows"] = jrows;
  write_json(fs::path(out) / "collision.json", report);
}

std::vector<Chart> charts(const std::vector<Row>& totals) {
  Chart agreement =
      make_chart("Collision verdicts against fcl::collide, all scenes", "m' (retained modes)", "rate", true);
  Chart timing =
      make_chart("Energy-only query time per pose (slowest scene)", "m' (retained modes)", "microseconds", true);
  timing.hlines.push_back({1000.0, "1 ms"});
  Series tp50{"median", {}, {}, Series::Style::line_points, ""}, tp99{"p99", {}, {}, Series::Style::line_points, ""};
  for (const std::string pred : {"bound", "estimate", "zero"}) {
    Series tpr{"true positive rate (" + pred + ")", {}, {}, Series::Style::line_points, ""};
    Series fpr{"false positive rate (" + pred + ")", {}, {}, Series::Style::line_points, ""};
    for (const Row& t : totals)
      if (t.predicate == pred) {
        tpr.x.push_back(double(t.modes)), tpr.y.push_back(t.c.tpr());
        fpr.x.push_back(double(t.modes)), fpr.y.push_back(t.c.fpr());
        if (pred == "bound") {
          tp50.x.push_back(double(t.modes)), tp50.y.push_back(t.p50_us);
          tp99.x.push_back(double(t.modes)), tp99.y.push_back(t.p99_us);
        }
      }
    agreement.series.push_back(tpr);
    agreement.series.push_back(fpr);
  }
  timing.series = {tp50, tp99};
  return {agreement, timing};
}

int run(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  const RunSpan span;
  span.announce("bench_collision", command_line(argc, argv));

  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(select_device(device_spec_from(o.device)));
  std::cout << "  device: " << describe_device(ctx.device.info) << "\n";
  PairOptions popt;
  popt.descriptors.progress = pass_progress_bars(std::cerr);
  popt.note = [](const std::string& m) { std::cerr << "  snapfit: " << m << "\n"; };

  std::vector<Row> rows;
  fs::create_directories(o.out);
  CsvFile poses_csv(fs::path(o.out) / "poses.csv",
                    "scene,pose,x,y,z,qw,qx,qy,qz,fcl_collides,distance_to_contact,modes,overlap,bound");
  for (const std::string& file : o.scene_files) {
    Scene scene = indicator_scene(load_scene(file));
    if (o.quick) {
      if (scene.grid.spacing) scene.grid.spacing = 2.0 * *scene.grid.spacing;
      if (scene.grid.resolution) scene.grid.resolution = std::max(8, *scene.grid.resolution / 2);
    }
    const bool rotates = scene.motion == Motion::six_dof;
    std::cout << "\n[" << file << "] " << scene.name << " (" << (rotates ? "6-DOF" : "translation") << ")\n"
              << std::flush;
    const AssemblyPair pair = build_assembly_pair(scene, ctx, fft, popt);
    const double h = pair.spectra.spacing;
    QueryVariant variant = query_variant_for(scene);
    variant.force = variant.torque = false;  // the predicate needs the energy alone
    auto engine = make_query_engine(ctx, pair.spectra, variant);
    const TruncationTails tails = truncation_tails(pair.spectra);
    const std::vector<Pose> poses = scene_poses(scene, *engine, o.pose_count, h, pair);
    const Truth truth = fcl_truth(pair, poses);
    std::size_t colliding = 0;
    for (int t : truth.collides) colliding += std::size_t(t);
    std::cout << "  FCL: " << colliding << " colliding, " << poses.size() - colliding << " free\n";
    measure_modes(file, *engine, tails, h, poses, truth, poses_csv, rows);
  }
  const std::vector<Row> totals = totals_of(rows);
  nlohmann::json record = run_record(argc, argv, describe_device(ctx.device.info), span.load_start);
  record["quick"] = o.quick;
  write_results(o.out, rows, totals, record);
  const std::string page = write_charts(o.out, "bench_collision: seed 001's collision predicate against FCL",
                                        command_line(argc, argv), charts(totals));
  std::cout << "wrote " << o.out << "/collision.csv, poses.csv, collision.json and " << page << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return snapfit::bench::guarded_main("bench_collision", [&] { return run(argc, argv); });
}
