// Benchmark of per-pose queries (include/snapfit/query.h), batched queries, full
// translational maps (engine/maps/full_map.h) and a roofline of the query kernel against
// this device's measured memory bandwidth and arithmetic peak.
//
//   bench_queries --help lists its options.
//
// What is measured, on the selected OpenCL device, for the scene (default
// scenes/default.json; its descriptor fields come from the field cache or are computed
// once, with progress bars):
//   1. latency   wall clock around QueryEngine::query(pose), p50 / p99 / max in
//                microseconds, N repetitions (default 2000, --quick 300) after 100
//                warm-up queries, at m' in {1, 1024, ..., 131072} (m' = 1: the fixed
//                cost of one query: pose arguments, launch, phase tables, read-back), for
//                  6dof_eft_trilinear   6-DOF energy + force + torque, trilinear (8 taps)
//                  6dof_eft_tricubic    6-DOF energy + force + torque, Catmull-Rom (64 taps)
//                  6dof_eft_trilinear_half, 6dof_eft_tricubic_half   the same with the
//                                       spectrum cube stored as half floats
//                  6dof_ef_trilinear    6-DOF energy + force, trilinear
//                  translation_ef       translation only, energy + force
//                The translation-only engine runs on the same spectra
//                (QueryVariant{force, torque = false, translation_only = true}): its
//                weights fold S1(w) S2(-w) and no spectrum of part 2 is read, so it is
//                exactly what a translation scene would run. Poses: samples along the
//                scene's trajectory with small random perturbations (fixed seed), all
//                different within a sweep point; the translation-only poses keep R = I.
//   2. throughput  query_batch poses per second against batch size {1, 16, 256, 4096} (--quick: to 256)
//                at m' in {4096, 32768} (a point whose one batch would take longer than
//                30 s, 3 s with --quick, predicted from its latency, is skipped).
//   3. maps      translational_energy_map (all modes) at the scene's FFT grid:
//                rotations per second, cold (first call) and warm.
//   4. roofline  bytes and flops per mode counted from kernels/pose_query.cl (see
//                cost_model below), times m'; the device's memory bandwidth (copy and
//                read-reduce kernels over a 256 MiB buffer, best of 5) and arithmetic
//                peak (independent fma chains on float4 / float8, best of 5), measured
//                with the kernels of kernels/device_limits.cl; achieved GB/s and GFLOP/s
//                per variant at m' = 32768, from the single-query p50 and from the
//                largest batch.
//   5. targets   6-DOF E+F+T at m' >= 32768 with p99 <= 1 ms, per scheme; translation
//                only >= 10x faster than 6-DOF at the same m'. Seed 000's figure (1 kHz at
//                m' = 4096 on a Tesla K20c, translation only) is listed as published, not
//                measured here. PoCL's single-threaded driver is visible as well
//                (--device basic): it runs each query in the calling thread, as the haptic
//                loop does (scheduler/tuning/device_choice.h), without the multi-threaded
//                driver's dispatch to worker threads (0.02-0.07 ms per launch here).
// Output in DIR (default results/bench_queries): queries.csv, throughput.csv,
// queries.json (everything, with device, driver, load averages, command line, date) and
// charts.html: latency per variant, p99 of all variants, throughput, roofline.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/progress.h"
#include "engine/maps/full_map.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/spectra/fft3d.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/bench_poses.h"
#include "perf/device_limits.h"
#include "perf/quiet_guard.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/error.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace {

using namespace snapfit::bench;  // perf/*.h: tables, contention, quiet guard, poses, limits
using snapfit::Interpolation;
using snapfit::Pose;
using snapfit::QueryEngine;
using snapfit::QueryVariant;
using Clock = std::chrono::steady_clock;

// ---------------------------------------------------------------- command line

struct Args : CommonArgs {
  std::string scene = "scenes/default.json";
  int repeats = 0;                    // 0: 2000, or 300 with --quick
  bool latency_only = false;          // sections 1 and 5 only
  std::vector<std::size_t> modes;     // empty: the default m' list
  std::vector<std::string> variants;  // empty: every variant
};

Args parse_args(int argc, char** argv) {
  Args a;
  a.out = "results/bench_queries";
  a.command_line = command_line(argc, argv);
  CLI::App app{"Per-pose queries, batched queries, full translational maps and a roofline of the query kernel",
               "bench_queries"};
  add_common_options(app, a.quick, a.device, a.out,
                     "a few m' values, 300 repetitions (under a minute once fields are cached)");
  app.add_option("--scene", a.scene, "scene")->check(non_empty());
  app.add_option("--repeats", a.repeats, "timed queries per latency point (0: 2000, --quick 300)")
      ->check(CLI::Range(1, 10000000));
  app.add_flag("--latency-only", a.latency_only,
               "per-query latency and targets only (no batches, maps, device limits, roofline)");
  app.add_option("--modes", a.modes, "comma-separated m' values for the latency points (default 1,1024,...,131072)")
      ->delimiter(',')
      ->check(snapfit::cli::positive_number());
  app.add_option("--variants", a.variants,
                 "comma-separated variant keys (default all: 6dof_eft_trilinear, 6dof_eft_tricubic, "
                 "6dof_eft_trilinear_half, 6dof_eft_tricubic_half, 6dof_ef_trilinear, translation_ef)")
      ->delimiter(',');
  parse(app, argc, argv);
  return a;
}

// ---------------------------------------------------------------- variants and cost model

struct VariantSpec {
  std::string key, label;
  QueryVariant variant;
};

std::vector<VariantSpec> variant_specs() {
  return {
      {"6dof_eft_trilinear", "6-DOF E+F+T trilinear", QueryVariant{true, true, false, Interpolation::trilinear}},
      {"6dof_eft_tricubic", "6-DOF E+F+T tricubic", QueryVariant{true, true, false, Interpolation::tricubic}},
      {"6dof_eft_trilinear_half", "6-DOF E+F+T trilin half",
       QueryVariant{true, true, false, Interpolation::trilinear, true}},
      {"6dof_eft_tricubic_half", "6-DOF E+F+T tricub half",
       QueryVariant{true, true, false, Interpolation::tricubic, true}},
      {"6dof_ef_trilinear", "6-DOF E+F trilinear", QueryVariant{true, false, false, Interpolation::trilinear}},
      {"translation_ef", "translation-only E+F", QueryVariant{true, false, true, Interpolation::trilinear}},
  };
}

// Bytes and flops per retained mode, counted from kernels/pose_query.cl (one work-item
// iteration of the mode loop). Bytes: every global load the loop issues, counted once
// per mode as if nothing were cached (the "requested" traffic; the compact cube and the
// phase tables are small enough to stay in cache on a CPU, so DRAM traffic is lower):
//   6-DOF: modes[m] float4 16 B (weight and packed k), 3 phase-table lookups 3 x 8 B
//          (local memory)                                                  = 40 B
//          TAPS^3 cube taps x sizeof(Sample): float8 (32 B) with torque, float2 (8 B)
//          without; half that with the half-float cube
//   translation only (x-line intervals, engine/query/translation_lines.h): per node of the
//          selected intervals, weight 8 B + x table 8 B (local) = 16 B; flops per node:
//          complex multiply 6, 2 adds, 2 fma (kx terms) 4 = 12 (the masked lanes of each
//          line's last 8-wide chunk and the per-line sums are not counted)
// Both are counted per evaluated term (QueryEngine::evaluated_terms: a record or a
// line node, one per conjugate pair when pairs are folded) and scaled by terms per mode.
// Flops: an add, a multiply or a subtraction is 1, an fma 2; integer index arithmetic,
// floor and conversions are not counted:
//   phase: 3 complex multiplies (4 mul + 2 add each)                           18
//   6-DOF: w' = -R^T w (9 mul + 6 add) 15, u = w' L 3;
//          axis weights per axis: trilinear 2, Catmull-Rom 20 (t^2, t^3 and four cubics);
//          taps: per (z, y) pair one wy*wz multiply (TAPS^2), per tap one wx*wyz
//          multiply and one multiply-add per Sample component (8 or 2): TAPS^3 (1 + 2c);
//          term *= v: one complex multiply 6
//   torque: 3 complex multiplies 18, cross product of imaginary parts 9, *(-2 pi) and += 6
//   f += term 2; force += -2 pi term.y w: 1 + 3 + 3 = 7
// Per query on top (not per mode): 3 (2 h + 1) sincos per work-group for the phase
// tables, 8 floats per work-group read back, and the work-group reductions.
struct Cost {
  double bytes = 0, flops = 0;
  std::string bytes_detail, flops_detail;
};

Cost cost_model(const QueryVariant& v, double terms_per_mode) {
  Cost c;
  const double stream = 16 + 3 * 8;
  const double phase = 18, accumulate = 2, force = v.force ? 7 : 0;
  const std::string per_mode = ", x " + fmt(terms_per_mode, 3) + " terms per mode";
  if (v.translation_only) {
    c.bytes = 16 * terms_per_mode;
    c.flops = 12 * terms_per_mode;
    c.bytes_detail = "16 per line node (weight 8 + x table 8)" + per_mode;
    c.flops_detail = "12 per line node" + per_mode;
    return c;
  }
  const int taps = v.interpolation == Interpolation::tricubic ? 4 : 2;
  const int comps = v.torque ? 8 : 2;
  const double taps3 = double(taps) * taps * taps;
  const double gather_bytes = taps3 * comps * (v.half_cube ? 2 : 4);
  const double rotate = 15 + 3;
  const double weights = 3 * (taps == 4 ? 20 : 2);
  const double gather = taps * taps + taps3 * (1 + 2 * comps);
  const double torque = v.torque ? 18 + 9 + 6 : 0;
  c.bytes = stream + gather_bytes;
  c.flops = phase + rotate + weights + gather + 6 + torque + accumulate + force;
  c.bytes_detail = "40 stream + " + fmt(taps3, 3) + " taps x " + std::to_string(comps * (v.half_cube ? 2 : 4)) +
                   " B = " + fmt(c.bytes, 5) + per_mode;
  c.flops_detail = "18 phase + 18 rotate + " + fmt(weights, 3) + " weights + " + fmt(gather, 5) + " gather + 6 + " +
                   fmt(torque, 3) + " torque + 2 sum + 7 force = " + fmt(c.flops, 5) + per_mode;
  c.bytes *= terms_per_mode;
  c.flops *= terms_per_mode;
  return c;
}

// ---------------------------------------------------------------- geometry of the spectra

// |w| of every FFT node, sorted (the engine's low-pass order).
std::vector<float> sorted_mode_radii(const snapfit::PairSpectra& s) {
  const auto& d = s.dims;
  std::vector<double> fx(d[0]), fy(d[1]), fz(d[2]);
  for (std::size_t i = 0; i < d[0]; ++i) fx[i] = s.frequency(0, i);
  for (std::size_t i = 0; i < d[1]; ++i) fy[i] = s.frequency(1, i);
  for (std::size_t i = 0; i < d[2]; ++i) fz[i] = s.frequency(2, i);
  std::vector<float> r;
  r.reserve(d[0] * d[1] * d[2]);
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      for (std::size_t x = 0; x < d[0]; ++x)
        r.push_back(float(std::sqrt(fx[x] * fx[x] + fy[y] * fy[y] + fz[z] * fz[z])));
  std::sort(r.begin(), r.end());
  return r;
}

// The working set of one query at m' (what engine/pose_query.cpp uploads and the kernel
// reads): the mode records (16 B per evaluated term; translation only: 8 B per line node,
// plus 16 B per line record, not counted), the compact cube of part 2's spectrum (as ensure_cube
// builds it fresh for this m') and the three phase tables.
struct Footprint {
  double mode_bytes = 0, cube_bytes = 0, table_bytes = 0;
  std::array<int, 3> cube_dims{};
};
Footprint footprint(const snapfit::PairSpectra& s, const std::vector<float>& radii, std::size_t m, std::size_t terms,
                    const QueryVariant& v) {
  Footprint f;
  m = std::clamp<std::size_t>(m, 1, radii.size());
  f.mode_bytes = v.translation_only ? 8.0 * double(terms) : 16.0 * double(terms);
  const double r = radii[m - 1];
  int table_half = 0;
  for (int a = 0; a < 3; ++a) table_half = std::max(table_half, int(std::floor(r * s.length[a] + 1e-6)));
  f.table_bytes = 3.0 * (2 * table_half + 1) * 8;
  if (!v.translation_only) {
    const double radius = std::min(double(r) * 1.25, double(radii.back()));
    double nodes = 1;
    for (int a = 0; a < 3; ++a) {
      const int half = int(std::ceil(radius * s.length[a])) + 2;
      f.cube_dims[a] = 2 * half + 2;
      nodes *= f.cube_dims[a];
    }
    f.cube_bytes = nodes * (v.torque ? 32 : 8) * (v.half_cube ? 0.5 : 1.0);
  }
  return f;
}

// ---------------------------------------------------------------- measurements

struct LatencyRow {
  std::string key, label;
  QueryVariant variant;
  std::size_t modes = 0, modes_used = 0;
  std::size_t terms = 0;    // terms the kernel evaluates (conjugate pairs folded: about m' / 2)
  double set_modes_us = 0;  // one QueryEngine::set_modes(m') call after set_modes(1)
  int repeats = 0, warmup = 0;
  double p50 = 0, p99 = 0, max = 0, mean = 0, min = 0, p10 = 0, p90 = 0;  // microseconds
  std::size_t flagged = 0;
  Cost cost;
  Footprint fp;
  double load_before = 0, load_after = 0;
  double other_cores = 0;  // cores busy with other processes during the timed queries
  int attempts = 1;
};

LatencyRow measure_latency(QueryEngine& engine, const VariantSpec& spec, const std::vector<Pose>& poses,
                           std::size_t modes, int warmup, int repeats, std::size_t& cursor, double& sink) {
  LatencyRow r;
  r.key = spec.key;
  r.label = spec.label;
  r.variant = spec.variant;
  r.modes = modes;
  engine.set_modes(1);
  const auto s0 = Clock::now();
  engine.set_modes(modes);
  r.set_modes_us = std::chrono::duration<double, std::micro>(Clock::now() - s0).count();
  r.modes_used = engine.modes();
  r.terms = engine.evaluated_terms();
  r.warmup = warmup;
  r.repeats = repeats;
  r.load_before = load1();
  for (int i = 0; i < warmup; ++i) sink += engine.query(poses[cursor++ % poses.size()]).energy;
  std::vector<double> us(static_cast<std::size_t>(repeats));
  const CpuSample cpu0 = cpu_sample();
  for (int i = 0; i < repeats; ++i) {
    const Pose& pose = poses[cursor++ % poses.size()];
    const auto t0 = Clock::now();
    const snapfit::QueryResult q = engine.query(pose);
    us[static_cast<std::size_t>(i)] = std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
    if (q.flags != snapfit::query_ok) ++r.flagged;
    sink += q.energy;
  }
  r.other_cores = other_cores(cpu0, cpu_sample());
  r.load_after = load1();
  double sum = 0;
  for (double v : us) sum += v;
  std::sort(us.begin(), us.end());
  r.p50 = percentile(us, 0.5);
  r.p10 = percentile(us, 0.1);
  r.p90 = percentile(us, 0.9);
  r.p99 = percentile(us, 0.99);
  r.max = us.back();
  r.min = us.front();
  r.mean = sum / double(us.size());
  return r;
}

struct ThroughputRow {
  std::string key, label;
  std::size_t modes = 0, batch = 0;
  int batches = 0;
  double seconds = 0;      // all timed batches
  double poses_per_s = 0;  // best batch
  double median_poses_per_s = 0;
  bool skipped = false;
  std::string note;
  double other_cores = 0;
  int attempts = 1;
};

struct MapRow {
  std::string interpolation;
  std::array<std::size_t, 3> dims{};
  double cold_s = 0;
  std::vector<double> warm_s;
  double warm_median_s = 0, rotations_per_s = 0;
  double other_cores = 0;
  int attempts = 1;
};

// ---------------------------------------------------------------- output

void write_csvs(const std::filesystem::path& dir, const std::vector<LatencyRow>& lat,
                const std::vector<ThroughputRow>& thr, const std::string& device) {
  CsvFile q(dir / "queries.csv",
            "variant,label,interpolation,torque,translation_only,modes,modes_used,repeats,warmup,p50_us,p99_us,max_us,"
            "mean_us,min_us,p10_us,p90_us,flagged,bytes_per_mode,flops_per_mode,gbs_at_p50,gflops_at_p50,cube_bytes,"
            "load_before,load_after,other_cores,device,source");
  for (const auto& r : lat) {
    const double s = r.p50 * 1e-6;
    const QueryVariant& v = r.variant;
    q.row(r.key, quoted(r.label),
          v.translation_only                           ? "none"
          : v.interpolation == Interpolation::tricubic ? "tricubic"
                                                       : "trilinear",
          v.torque, v.translation_only, r.modes, r.modes_used, r.repeats, r.warmup, r.p50, r.p99, r.max, r.mean, r.min,
          r.p10, r.p90, r.flagged, r.cost.bytes, r.cost.flops, r.cost.bytes * double(r.modes_used) / s * 1e-9,
          r.cost.flops * double(r.modes_used) / s * 1e-9, r.fp.cube_bytes, r.load_before, r.load_after, r.other_cores,
          quoted(device), "measured");
  }
  q.row("seed000_translation", quoted("seed 000: translation only, 1 kHz (1000 us per frame) on a Tesla K20c"),
        "none,0,1,4096,4096,,,,,,,,,,,,,,,,,,", quoted("NVIDIA Tesla K20c"), quoted("published, not measured here"));
  CsvFile t(dir / "throughput.csv",
            "variant,label,modes,batch,batches,seconds,poses_per_s_best,poses_per_s_median,skipped,other_cores,"
            "attempts,note");
  for (const auto& r : thr)
    t.row(r.key, quoted(r.label), r.modes, r.batch, r.batches, r.seconds, r.poses_per_s, r.median_poses_per_s,
          r.skipped, r.other_cores, r.attempts, quoted(r.note));
}

// ---------------------------------------------------------------- the sweep

struct Plan {
  std::vector<std::size_t> modes_list;  // m' of the latency points
  int repeats = 0, warmup = 100;
  std::vector<std::size_t> batch_modes, batch_sizes;
  double batch_cap_s = 0;  // a batch predicted to take longer is skipped
};

Plan plan_for(const Args& args) {
  Plan p;
  p.modes_list = !args.modes.empty() ? args.modes
                 : args.quick        ? std::vector<std::size_t>{1, 1024, 4096, 32768}
                                     : std::vector<std::size_t>{1, 1024, 4096, 8192, 16384, 32768, 65536, 131072};
  p.repeats = args.repeats > 0 ? args.repeats : (args.quick ? 300 : 2000);
  if (!args.latency_only) p.batch_modes = {4096, 32768};
  // --quick stops at 256: a 4096-pose batch takes seconds per point on a CPU.
  p.batch_sizes = args.quick ? std::vector<std::size_t>{1, 16, 256} : std::vector<std::size_t>{1, 16, 256, 4096};
  p.batch_cap_s = args.quick ? 3.0 : 30.0;
  return p;
}

std::vector<VariantSpec> selected_specs(const Args& args) {
  std::vector<VariantSpec> specs;
  for (const auto& spec : variant_specs())
    if (args.variants.empty() || std::find(args.variants.begin(), args.variants.end(), spec.key) != args.variants.end())
      specs.push_back(spec);
  if (specs.empty()) throw snapfit::Error("--variants: no known variant named (see --help)");
  return specs;
}

struct RoofRow {
  std::string key, label;
  std::size_t modes = 0;
  Cost cost;
  Footprint fp;
  double p50_us = 0, single_gbs = 0, single_gflops = 0;
  double batch = 0, batch_pps = 0, batch_gbs = 0, batch_gflops = 0;
};

// What the sections share: the command line, the sweep, the device and the scene's
// spectra, and the rows each section adds.
struct Bench {
  const Args& args;
  Plan plan;
  const snapfit::FftLibrary& fft;
  const snapfit::ComputeContext& ctx;
  const snapfit::Scene& scene;
  const snapfit::PairSpectra& spectra;
  std::vector<float> radii;
  std::vector<VariantSpec> specs;
  QuietGuard guard;
  double sink = 0;  // keeps the results alive
  std::vector<LatencyRow> latency;
  std::map<std::string, std::vector<Pose>> poses_of;
  std::map<std::string, std::size_t> rejected_of;
  std::map<std::string, std::unique_ptr<QueryEngine>> engines;
  std::vector<ThroughputRow> throughput;
  std::vector<MapRow> maps;
  DeviceLimits limits;
  double limits_others = 0;
  int limits_attempts = 1;
  std::vector<RoofRow> roof;
  nlohmann::json split = nlohmann::json::array();
  nlohmann::json targets;

  Bench(const Args& a, const snapfit::FftLibrary& f, const snapfit::ComputeContext& c, const snapfit::Scene& s,
        const snapfit::PairSpectra& sp)
      : args(a),
        plan(plan_for(a)),
        fft(f),
        ctx(c),
        scene(s),
        spectra(sp),
        radii(sorted_mode_radii(sp)),
        specs(selected_specs(a)) {}
  std::size_t total_modes() const { return spectra.dims[0] * spectra.dims[1] * spectra.dims[2]; }
  const LatencyRow* find_lat(const std::string& key, std::size_t m) const {
    for (const auto& r : latency)
      if (r.key == key && r.modes == m) return &r;
    return nullptr;
  }
};

// ---------------------------------------------------------------- 1. latency

void print_latency_row(const LatencyRow& r) {
  std::cout << "    m' " << pad(std::to_string(r.modes_used), 7) << "  p50 " << pad(fixed(r.p50), 9) << " us  p99 "
            << pad(fixed(r.p99), 9) << " us  max " << pad(fixed(r.max), 9) << " us  [p10 " << pad(fixed(r.p10), 8)
            << " p90 " << pad(fixed(r.p90), 8) << " mean " << pad(fixed(r.mean), 8) << "]  (load "
            << fixed(r.load_before, 2) << " -> " << fixed(r.load_after, 2) << ", others " << fixed(r.other_cores, 2)
            << " cores; set_modes from 1: " << fixed(r.set_modes_us, 0) << " us"
            << (r.attempts > 1 ? ", attempt " + std::to_string(r.attempts) : "")
            << (r.flagged ? ", FLAGGED " + std::to_string(r.flagged) : "") << ")\n"
            << std::flush;
}

// One variant's engine, its usable poses and its latency at every m' of the sweep.
void measure_variant_latency(Bench& b, const VariantSpec& spec, std::size_t pose_count) {
  auto engine = make_query_engine(b.ctx, b.spectra, spec.variant);
  engine->set_modes(1024);
  // Within 0.5 spacings and 0.5 degrees of the trajectory; translation only: R = I.
  const auto all =
      trajectory_poses(b.scene, pose_count, 12345u, 0.5 * b.spectra.spacing, 0.5, !spec.variant.translation_only);
  std::size_t rejected = 0;
  const std::vector<Pose>& poses = b.poses_of[spec.key] = usable_poses(*engine, all, rejected);
  b.rejected_of[spec.key] = rejected;
  if (poses.empty()) throw snapfit::Error("no usable pose for " + spec.label + " (all outside the grid?)");
  std::cout << "  " << padr(spec.label, 24) << " " << poses.size() << " poses (" << rejected
            << " outside the padded box dropped)\n";
  std::size_t cursor = 0;
  for (std::size_t m : b.plan.modes_list) {
    double others = 0;
    int attempts = 1;
    LatencyRow r = b.guard.run(
        spec.key + " m' " + std::to_string(m),
        [&] { return measure_latency(*engine, spec, poses, m, b.plan.warmup, b.plan.repeats, cursor, b.sink); }, others,
        attempts);
    r.attempts = attempts;
    r.cost = cost_model(spec.variant, double(r.terms) / double(std::max<std::size_t>(r.modes_used, 1)));
    r.fp = footprint(b.spectra, b.radii, r.modes_used, r.terms, spec.variant);
    print_latency_row(r);
    b.latency.push_back(r);
  }
  b.engines[spec.key] = std::move(engine);
}

void measure_latencies(Bench& b) {
  if (b.args.quick) b.guard.max_retries = 0;  // --quick only records the contention
  std::cout << "\n[1] per-query latency: " << b.plan.repeats << " timed queries after " << b.plan.warmup
            << " warm-up per point (wall clock around engine.query)\n";
  const std::size_t pose_count = std::max<std::size_t>(4096, std::size_t(b.plan.repeats) + b.plan.warmup);
  for (const auto& spec : b.specs) measure_variant_latency(b, spec, pose_count);
}

// ---------------------------------------------------------------- 2. throughput

// Poses per second of query_batch with batches of `size` poses: at least 3 batches (2
// when one is predicted over 5 s) and 0.2 s (--quick) or 1 s.
ThroughputRow measure_batches(Bench& b, QueryEngine& engine, const std::vector<Pose>& poses, ThroughputRow t,
                              double predicted) {
  const std::size_t size = t.batch;
  std::vector<Pose> batch(size);
  std::size_t offset = 0;
  auto fill = [&] {
    for (std::size_t i = 0; i < size; ++i) batch[i] = poses[(offset + i) % poses.size()];
    offset += 7919;
  };
  fill();
  // Warm-up (buffer growth) with the whole batch unless that would take long.
  if (predicted < 2.0)
    for (const auto& q : engine.query_batch(batch)) b.sink += q.energy;
  std::vector<double> rates;
  const double min_time = b.args.quick ? 0.2 : 1.0;
  const int min_batches = predicted > 5.0 ? 2 : 3, max_batches = size == 1 ? 2000 : 200;
  double spent = 0;
  while ((spent < min_time || int(rates.size()) < min_batches) && int(rates.size()) < max_batches) {
    fill();
    const auto tb = Clock::now();
    const auto res = engine.query_batch(batch);
    const double s = seconds_since(tb);
    for (const auto& q : res) b.sink += q.energy;
    spent += s;
    rates.push_back(double(size) / s);
    if (s > b.plan.batch_cap_s) break;
  }
  t.batches = int(rates.size());
  t.seconds = spent;
  t.poses_per_s = *std::max_element(rates.begin(), rates.end());
  t.median_poses_per_s = median(rates);
  return t;
}

// One point of the throughput table: skipped when its batch is predicted (from the
// single-query p50 at m') to take longer than the cap.
ThroughputRow throughput_point(Bench& b, const VariantSpec& spec, QueryEngine& engine, std::size_t m,
                               std::size_t size) {
  ThroughputRow t;
  t.key = spec.key;
  t.label = spec.label;
  t.modes = engine.modes();
  t.batch = size;
  const LatencyRow* lr = b.find_lat(spec.key, m);
  const double predicted = lr ? lr->p50 * 1e-6 * double(size) : 0.0;
  if (predicted > b.plan.batch_cap_s) {
    t.skipped = true;
    t.note = "skipped: one batch predicted " + fixed(predicted, 0) + " s from the single-query p50";
    std::cout << "  " << padr(spec.label, 24) << " m' " << pad(std::to_string(m), 6) << " batch "
              << pad(std::to_string(size), 5) << "  " << t.note << "\n";
    return t;
  }
  double others = 0;
  int attempts = 1;
  t = b.guard.run(
      spec.key + " m' " + std::to_string(m) + " batch " + std::to_string(size),
      [&] { return measure_batches(b, engine, b.poses_of[spec.key], t, predicted); }, others, attempts);
  t.other_cores = others;
  t.attempts = attempts;
  std::cout << "  " << padr(spec.label, 24) << " m' " << pad(std::to_string(t.modes), 6) << " batch "
            << pad(std::to_string(size), 5) << "  " << pad(fmt(t.median_poses_per_s, 4), 9) << " poses/s median, "
            << pad(fmt(t.poses_per_s, 4), 9) << " best (" << t.batches << " batches, " << fixed(t.seconds, 2)
            << " s; others " << fixed(t.other_cores, 2) << " cores"
            << (t.attempts > 1 ? ", attempt " + std::to_string(t.attempts) : "") << ")\n"
            << std::flush;
  return t;
}

void measure_throughput(Bench& b) {
  std::cout << "\n[2] batched throughput (query_batch), poses per second\n";
  for (const auto& spec : b.specs) {
    QueryEngine& engine = *b.engines[spec.key];
    for (std::size_t m : b.plan.batch_modes) {
      engine.set_modes(m);
      for (std::size_t size : b.plan.batch_sizes) b.throughput.push_back(throughput_point(b, spec, engine, m, size));
    }
  }
}

// ---------------------------------------------------------------- 3. full maps

// Cold (the first call: program load and FFT plan bake) and 4 warm times of the full
// translational map at the FFT grid.
MapRow measure_map(Bench& b, Interpolation interp, const std::vector<Pose>& rot_poses, std::size_t& next) {
  MapRow row;
  row.interpolation = interp == Interpolation::tricubic ? "tricubic" : "trilinear";
  row.dims = b.spectra.dims;
  double cold = std::numeric_limits<double>::quiet_NaN(), others = 0;
  int attempts = 1;
  const auto rotation = [&] { return rot_poses[next++ % rot_poses.size()].rotation.toRotationMatrix(); };
  row.warm_s = b.guard.run(
      "maps " + row.interpolation, [&] { return time_full_maps(b.fft, b.ctx, b.spectra, interp, 4, cold, rotation); },
      others, attempts);
  row.cold_s = cold;
  row.other_cores = others;
  row.attempts = attempts;
  row.warm_median_s = median(row.warm_s);
  row.rotations_per_s = 1.0 / row.warm_median_s;
  return row;
}

void measure_maps(Bench& b) {
  const auto& dims = b.spectra.dims;
  std::cout << "\n[3] full translational maps (translational_energy_map, all modes) at the FFT grid " << dims[0] << "x"
            << dims[1] << "x" << dims[2] << "\n";
  if (b.args.quick)
    std::cout << "  skipped with --quick (a cold map bakes an FFT plan for the full grid: a minute on a CPU)\n";
  if (b.args.latency_only || b.args.quick) return;
  const auto rot_poses = trajectory_poses(b.scene, 16, 777u, 0.5 * b.spectra.spacing, 0.5);
  std::size_t next = 0;
  for (Interpolation interp : {Interpolation::trilinear, Interpolation::tricubic}) {
    const MapRow row = measure_map(b, interp, rot_poses, next);
    std::cout << "  " << padr(row.interpolation, 10) << " cold " << fixed(row.cold_s, 3) << " s, warm median "
              << fixed(row.warm_median_s, 3) << " s over " << row.warm_s.size() << " -> " << fmt(row.rotations_per_s, 3)
              << " rotations/s (" << fmt(double(b.total_modes()) * row.rotations_per_s / 1e6, 3)
              << " M translations/s; others " << fixed(row.other_cores, 2) << " cores)\n"
              << std::flush;
    b.maps.push_back(row);
  }
}

// ---------------------------------------------------------------- 4. roofline

void print_limits(const Bench& b) {
  const DeviceLimits& limits = b.limits;
  std::cout << "  (other processes used " << fixed(b.limits_others, 2) << " cores meanwhile"
            << (b.limits_attempts > 1 ? ", attempt " + std::to_string(b.limits_attempts) : "") << ")\n";
  for (const auto& r : limits.bandwidth)
    std::cout << "  " << padr(r.name, 13) << pad(fixed(r.best, 1), 8) << " GB/s   (" << r.detail
              << (r.name == "read_cached" ? std::string() : ", " + fixed(limits.buffer_mib, 0) + " MiB") << ")\n";
  for (const auto& r : limits.compute)
    std::cout << "  " << padr(r.name, 13) << pad(fixed(r.best, 1), 8) << " GFLOP/s (" << r.detail << ")\n";
  const double bw = limits.read_gbs, peak = limits.peak_gflops;
  std::cout << "  limits used below: read bandwidth " << fixed(bw, 1) << " GB/s (the query kernel only reads), peak "
            << fixed(peak, 1) << " GFLOP/s, ridge at " << fmt(peak / bw, 3) << " flop/B\n";
}

// A variant's achieved GB/s and GFLOP/s from its single-query p50 and its largest batch.
RoofRow roof_row(const Bench& b, const VariantSpec& spec, const LatencyRow& lr) {
  RoofRow rr;
  rr.key = spec.key;
  rr.label = spec.label;
  rr.modes = lr.modes_used;
  rr.cost = lr.cost;
  rr.fp = lr.fp;
  rr.p50_us = lr.p50;
  const double bytes = rr.cost.bytes * double(rr.modes), flops = rr.cost.flops * double(rr.modes);
  rr.single_gbs = bytes / (lr.p50 * 1e-6) * 1e-9;
  rr.single_gflops = flops / (lr.p50 * 1e-6) * 1e-9;
  for (const auto& t : b.throughput)
    if (t.key == spec.key && t.modes == lr.modes_used && !t.skipped && double(t.batch) > rr.batch) {
      rr.batch = double(t.batch);
      rr.batch_pps = t.median_poses_per_s;
    }
  rr.batch_gbs = bytes * rr.batch_pps * 1e-9;
  rr.batch_gflops = flops * rr.batch_pps * 1e-9;
  return rr;
}

void print_roof_row(const Bench& b, const RoofRow& rr) {
  const double bw = b.limits.read_gbs, peak = b.limits.peak_gflops;
  std::cout << "  " << padr(rr.label, 24) << pad(fmt(rr.cost.bytes, 5), 8) << pad(fmt(rr.cost.flops, 5), 10)
            << pad(fmt(rr.cost.flops / rr.cost.bytes, 2), 8) << pad(fixed(rr.fp.cube_bytes / 1024, 0), 10) << " | "
            << pad(fixed(rr.p50_us, 0), 9) << pad(fixed(rr.single_gbs, 2), 8)
            << pad(fixed(100 * rr.single_gbs / bw, 1), 7) << pad(fixed(rr.single_gflops, 2), 9)
            << pad(fixed(100 * rr.single_gflops / peak, 1), 7) << " | " << pad(fmt(rr.batch, 4), 6)
            << pad(fixed(rr.batch_gbs, 2), 8) << pad(fixed(100 * rr.batch_gbs / bw, 1), 7)
            << pad(fixed(rr.batch_gflops, 2), 9) << pad(fixed(100 * rr.batch_gflops / peak, 1), 7)
            << "   (single query: " << fixed(100 * rr.single_gbs / b.limits.cached_gbs, 1)
            << "% of cache-resident reads)\n";
}

constexpr std::size_t kRoofModes = 32768;

void measure_roofline(Bench& b) {
  std::cout << "\n[4] device limits (best of 5) and roofline\n";
  if (!b.args.latency_only)
    b.limits = b.guard.run(
        "the device limits", [&] { return measure_limits(b.ctx, b.args.quick); }, b.limits_others, b.limits_attempts);
  print_limits(b);
  std::cout << "  per mode (counting in the header of perf/bench_queries.cpp), at m' = " << kRoofModes << ":\n";
  std::cout << "  " << padr("variant", 24) << pad("B/mode", 8) << pad("flop/mode", 10) << pad("flop/B", 8)
            << pad("cube KiB", 10) << " | " << pad("p50 us", 9) << pad("GB/s", 8) << pad("%BW", 7) << pad("GFLOP/s", 9)
            << pad("%peak", 7) << " | " << pad("batch", 6) << pad("GB/s", 8) << pad("%BW", 7) << pad("GFLOP/s", 9)
            << pad("%peak", 7) << "\n";
  for (const auto& spec : b.specs) {
    const LatencyRow* lr = b.find_lat(spec.key, kRoofModes);
    if (!lr) continue;
    b.roof.push_back(roof_row(b, spec, *lr));
    print_roof_row(b, b.roof.back());
  }
  for (const auto& spec : b.specs) {
    const LatencyRow* lr = b.find_lat(spec.key, kRoofModes);
    if (!lr) continue;  // not measured at this m'
    const Cost& c = lr->cost;
    std::cout << "    " << padr(spec.label, 24) << " bytes: " << c.bytes_detail << "; flops: " << c.flops_detail
              << "\n";
  }
}

// Where the time of a 6-DOF E+F+T query goes: p50 differences between the variants.
void time_split(Bench& b) {
  std::cout << "\n  where the time of one 6-DOF E+F+T query goes (p50 differences between variants, us):\n  "
            << pad("m'", 7) << pad("fixed", 9) << pad("stream", 9) << pad("rot+2^3", 9) << pad("float8", 9)
            << pad("E+F+T tri", 11) << pad("4^3 taps", 10) << pad("E+F+T cub", 11) << "\n";
  for (std::size_t m : b.plan.modes_list) {
    const LatencyRow *t1 = b.find_lat("translation_ef", 1), *t = b.find_lat("translation_ef", m),
                     *ef = b.find_lat("6dof_ef_trilinear", m), *eft = b.find_lat("6dof_eft_trilinear", m),
                     *cub = b.find_lat("6dof_eft_tricubic", m);
    if (m < 1024 || !t1 || !t || !ef || !eft || !cub) continue;
    const double fixed_us = t1->p50, stream = t->p50 - t1->p50, rot = ef->p50 - t->p50, f8 = eft->p50 - ef->p50,
                 taps = cub->p50 - eft->p50;
    b.split.push_back({{"modes", m},
                       {"fixed_us", fixed_us},
                       {"mode_stream_and_phase_us", stream},
                       {"rotation_weights_trilinear_float2_gather_us", rot},
                       {"torque_float8_instead_of_float2_us", f8},
                       {"tricubic_64_taps_instead_of_8_us", taps},
                       {"eft_trilinear_p50_us", eft->p50},
                       {"eft_tricubic_p50_us", cub->p50}});
    std::cout << "  " << pad(std::to_string(m), 7) << pad(fixed(fixed_us, 0), 9) << pad(fixed(stream, 0), 9)
              << pad(fixed(rot, 0), 9) << pad(fixed(f8, 0), 9) << pad(fixed(eft->p50, 0), 11) << pad(fixed(taps, 0), 10)
              << pad(fixed(cub->p50, 0), 11) << "\n";
  }
  std::cout
      << "  (fixed: translation-only at m' = 1 - pose arguments, launch, phase tables, read-back; stream: translation\n"
         "   E+F above that - the per-mode arrays, table lookups and complex products; rot+2^3: 6-DOF E+F trilinear\n"
         "   above translation - rotation, weights and 8 float2 taps; float8: E+F+T above E+F; 4^3 taps: tricubic\n"
         "   above trilinear E+F+T)\n";
}

// ---------------------------------------------------------------- 5. targets

// Largest m' per variant whose p99 stays within 1 ms (contiguous from 1024).
nlohmann::json reach_within_1ms(const Bench& b) {
  nlohmann::json reach = nlohmann::json::object();
  for (const auto& spec : b.specs) {
    std::size_t best = 0;
    bool all_below = true;
    for (std::size_t m : b.plan.modes_list) {
      const LatencyRow* r = b.find_lat(spec.key, m);
      if (!r || m < 1024) continue;
      if (r->p99 <= 1000.0) {
        if (all_below) best = r->modes_used;
      } else {
        all_below = false;
      }
    }
    reach[spec.key] = best;
    std::cout << "  " << padr(spec.label, 24)
              << " largest m' (of those measured, contiguous from 1024) with p99 <= 1 ms: "
              << (best ? std::to_string(best) : std::string("none")) << "\n";
  }
  return reach;
}

// 6-DOF E+F+T at m' = 32768 within a p99 of 1 ms, per scheme.
nlohmann::json six_dof_at_32768(const Bench& b) {
  nlohmann::json six = nlohmann::json::object();
  for (const std::string key :
       {"6dof_eft_trilinear", "6dof_eft_tricubic", "6dof_eft_trilinear_half", "6dof_eft_tricubic_half"}) {
    const LatencyRow* r = b.find_lat(key, 32768);
    if (!r) continue;
    const bool met = r->p99 <= 1000.0;
    six[key] = {{"p99_us_at_32768", num(r->p99)}, {"met", met}};
    std::cout << "  target 6-DOF E+F+T m' >= 32768 at p99 <= 1 ms (" << key << "): "
              << "p99 " + fixed(r->p99, 0) + " us -> " + (met ? "MET" : "NOT MET") << "\n";
  }
  return six;
}

// Translation only against 6-DOF E+F+T trilinear at the same m' (target >= 10x).
nlohmann::json translation_speedup(const Bench& b) {
  nlohmann::json ratios = nlohmann::json::array();
  std::cout << "  translation-only speed-up over 6-DOF E+F+T trilinear at the same m' (p50 ratio / p99 ratio; target "
               ">= 10x):\n";
  for (std::size_t m : b.plan.modes_list) {
    const LatencyRow* a = b.find_lat("6dof_eft_trilinear", m);
    const LatencyRow* t = b.find_lat("translation_ef", m);
    const LatencyRow* c = b.find_lat("6dof_ef_trilinear", m);
    if (!a || !t) continue;
    const double rp50 = a->p50 / t->p50, rp99 = a->p99 / t->p99;
    const double rc = c ? c->p50 / t->p50 : std::numeric_limits<double>::quiet_NaN();
    // Kernel-only estimate: both minus the fixed cost of a query (m' = 1).
    const LatencyRow* a1 = b.find_lat("6dof_eft_trilinear", 1);
    const LatencyRow* t1 = b.find_lat("translation_ef", 1);
    double rk = std::numeric_limits<double>::quiet_NaN();
    if (a1 && t1 && m > 1 && t->p50 - t1->p50 > 0) rk = (a->p50 - a1->p50) / (t->p50 - t1->p50);
    ratios.push_back({{"modes", m},
                      {"p50_ratio", num(rp50)},
                      {"p99_ratio", num(rp99)},
                      {"p50_ratio_vs_6dof_ef", num(rc)},
                      {"marginal_ratio_above_fixed_cost", num(rk)},
                      {"met", rp50 >= 10.0 && rp99 >= 10.0}});
    std::cout << "    m' " << pad(std::to_string(m), 7) << "  " << pad(fixed(rp50, 2), 7) << "x / "
              << pad(fixed(rp99, 2), 7) << "x  " << ((rp50 >= 10.0 && rp99 >= 10.0) ? "MET" : "not met")
              << "   (vs 6-DOF E+F: " << fixed(rc, 2)
              << "x; above the m'=1 fixed cost: " << (std::isfinite(rk) ? fixed(rk, 2) + "x" : std::string("-"))
              << ")\n";
  }
  return ratios;
}

void check_targets(Bench& b) {
  std::cout << "\n[5] targets\n";
  b.targets["largest_modes_within_1ms_p99"] = reach_within_1ms(b);
  b.targets["six_dof_32768_p99_1ms"] = six_dof_at_32768(b);
  b.targets["translation_speedup"] = translation_speedup(b);
  const LatencyRow* t4096 = b.find_lat("translation_ef", 4096);
  std::cout << "  seed 000 (published, not measured here): translation only, m' = 4096, 1 kHz (1000 us per frame) on a"
               " NVIDIA Tesla K20c; here translation-only m' = 4096: "
            << (t4096 ? "p50 " + fixed(t4096->p50, 1) + " us, p99 " + fixed(t4096->p99, 1) + " us" : std::string("-"))
            << " on " << b.ctx.device.info.name << "\n";
  b.targets["published_seed000"] = {{"variant", "translation only"},
                                    {"modes", 4096},
                                    {"rate_hz", 1000},
                                    {"frame_us", 1000},
                                    {"device", "NVIDIA Tesla K20c"},
                                    {"source", "published, not measured here"}};
}

// ---------------------------------------------------------------- output

// The run as a whole (perf/bench_common.h), the most contention during a latency point
// and the pair's set-up.
struct RunRecord : RunSpan {
  double others_latency_max = 0, pair_s = 0;
  bool fields_from_cache = false;
};

nlohmann::json latency_json(const Bench& b) {
  nlohmann::json lj = nlohmann::json::array();
  for (const auto& r : b.latency)
    lj.push_back({{"variant", r.key},
                  {"label", r.label},
                  {"modes", r.modes},
                  {"modes_used", r.modes_used},
                  {"repeats", r.repeats},
                  {"warmup", r.warmup},
                  {"p50_us", r.p50},
                  {"p99_us", r.p99},
                  {"max_us", r.max},
                  {"mean_us", r.mean},
                  {"min_us", r.min},
                  {"p10_us", r.p10},
                  {"p90_us", r.p90},
                  {"set_modes_us", r.set_modes_us},
                  {"flagged", r.flagged},
                  {"bytes_per_mode", r.cost.bytes},
                  {"flops_per_mode", r.cost.flops},
                  {"cube_bytes", r.fp.cube_bytes},
                  {"cube_dims", r.fp.cube_dims},
                  {"mode_bytes", r.fp.mode_bytes},
                  {"table_bytes", r.fp.table_bytes},
                  {"load_before", r.load_before},
                  {"load_after", r.load_after},
                  {"other_cores", r.other_cores},
                  {"attempts", r.attempts},
                  {"source", "measured"}});
  lj.push_back({{"variant", "seed000_translation"},
                {"label", "seed 000: translation only on a Tesla K20c"},
                {"modes", 4096},
                {"rate_hz", 1000},
                {"frame_us", 1000},
                {"source", "published, not measured here"}});
  return lj;
}

nlohmann::json throughput_json(const Bench& b) {
  nlohmann::json tj = nlohmann::json::array();
  for (const auto& t : b.throughput)
    tj.push_back({{"variant", t.key},
                  {"modes", t.modes},
                  {"batch", t.batch},
                  {"batches", t.batches},
                  {"seconds", t.seconds},
                  {"poses_per_s_best", t.poses_per_s},
                  {"poses_per_s_median", t.median_poses_per_s},
                  {"skipped", t.skipped},
                  {"note", t.note},
                  {"other_cores", t.other_cores},
                  {"attempts", t.attempts}});
  return tj;
}

nlohmann::json maps_json(const Bench& b) {
  nlohmann::json mj = nlohmann::json::array();
  for (const auto& m : b.maps)
    mj.push_back({{"interpolation", m.interpolation},
                  {"fft_dims", m.dims},
                  {"cold_s", m.cold_s},
                  {"warm_s", m.warm_s},
                  {"warm_median_s", m.warm_median_s},
                  {"rotations_per_s", m.rotations_per_s},
                  {"translations_per_s", double(b.total_modes()) * m.rotations_per_s},
                  {"other_cores", m.other_cores},
                  {"attempts", m.attempts}});
  return mj;
}

nlohmann::json limits_json(const Bench& b) {
  const DeviceLimits& limits = b.limits;
  nlohmann::json limj;
  for (const auto& r : limits.bandwidth)
    limj["bandwidth"].push_back({{"kernel", r.name}, {"best_gbs", r.best}, {"runs_gbs", r.runs}, {"detail", r.detail}});
  for (const auto& r : limits.compute)
    limj["compute"].push_back(
        {{"kernel", r.name}, {"best_gflops", r.best}, {"runs_gflops", r.runs}, {"detail", r.detail}});
  limj["buffer_mib"] = limits.buffer_mib;
  limj["other_cores"] = b.limits_others;
  limj["attempts"] = b.limits_attempts;
  limj["cached_read_gbs"] = limits.cached_gbs;
  limj["cached_buffer_mib"] = limits.cached_mib;
  limj["read_gbs"] = limits.read_gbs;
  limj["best_gbs"] = limits.bandwidth_gbs;
  limj["peak_gflops"] = limits.peak_gflops;
  return limj;
}

nlohmann::json roofline_json(const Bench& b) {
  const double bw = b.limits.read_gbs, peak = b.limits.peak_gflops;
  nlohmann::json rj = nlohmann::json::array();
  for (const auto& r : b.roof)
    rj.push_back({{"variant", r.key},
                  {"modes", r.modes},
                  {"bytes_per_mode", r.cost.bytes},
                  {"flops_per_mode", r.cost.flops},
                  {"bytes_detail", r.cost.bytes_detail},
                  {"flops_detail", r.cost.flops_detail},
                  {"intensity_flop_per_byte", r.cost.flops / r.cost.bytes},
                  {"cube_bytes", r.fp.cube_bytes},
                  {"p50_us", r.p50_us},
                  {"single_gbs", r.single_gbs},
                  {"single_gflops", r.single_gflops},
                  {"single_fraction_bw", r.single_gbs / bw},
                  {"single_fraction_cached_bw", r.single_gbs / b.limits.cached_gbs},
                  {"single_fraction_peak", r.single_gflops / peak},
                  {"batch", r.batch},
                  {"batch_poses_per_s", r.batch_pps},
                  {"batch_gbs", r.batch_gbs},
                  {"batch_gflops", r.batch_gflops},
                  {"batch_fraction_bw", r.batch_gbs / bw},
                  {"batch_fraction_peak", r.batch_gflops / peak}});
  return rj;
}

// queries.json's header: the run, the machine, the device, the scene and the method.
nlohmann::json run_json(const Bench& b, const RunRecord& run) {
  const auto& args = b.args;
  const auto& dims = b.spectra.dims;
  nlohmann::json j = run.header("bench_queries", args.command_line, args.quick, b.ctx.device.info);
  j["other_cores_run"] = run.others_run;
  j["quiet_guard"] = {{"threshold_cores", b.guard.threshold},
                      {"max_retries", b.guard.max_retries},
                      {"retries", b.guard.retries},
                      {"waited_s", b.guard.waited_s}};
  j["other_cores_latency_max"] = run.others_latency_max;
  j["load_note"] =
      "/proc/loadavg; the benchmark itself keeps the device's worker threads busy, so the 1-minute load "
      "rises toward the number of cores during the run: judge other activity by loadavg_start and by the "
      "running/total process counts; other_cores = (machine busy CPU time - this process's CPU time) / wall "
      "time, from /proc/stat and /proc/self/stat";
  j["scene"] = {{"file", args.scene},
                {"name", b.scene.name},
                {"fft_dims", {dims[0], dims[1], dims[2]}},
                {"max_modes", b.total_modes()},
                {"spacing", b.spectra.spacing},
                {"units", b.scene.units},
                {"length", {b.spectra.length.x(), b.spectra.length.y(), b.spectra.length.z()}},
                {"fields_from_cache", run.fields_from_cache},
                {"pair_seconds", run.pair_s}};
  j["method"] = {
      {"latency", "wall clock (steady_clock) around QueryEngine::query(pose); " + std::to_string(b.plan.warmup) +
                      " warm-up queries then " + std::to_string(b.plan.repeats) +
                      " timed per point; poses along the scene trajectory with +-0.5 spacing and up to 0.5 deg "
                      "random perturbation (translation only: R = I); percentiles nearest-rank"},
      {"throughput", "query_batch wall clock per batch; at least 3 batches and " +
                         std::string(args.quick ? "0.2" : "1") + " s per point; median and best batch"},
      {"maps",
       "translational_energy_map(all modes) wall clock, includes program load, FFT plan bake, "
       "uploads, inverse FFT, read-back and host re-ordering"},
      {"roofline",
       "bytes = global loads requested per mode (no cache reuse), flops = adds/muls (fma = 2) "
       "per mode, from kernels/pose_query.cl; see perf/bench_queries.cpp cost_model"}};
  return j;
}

nlohmann::json report_json(const Bench& b, const RunRecord& run) {
  nlohmann::json j = run_json(b, run);
  j["latency"] = latency_json(b);
  j["poses"] = nlohmann::json::object();
  for (const auto& [k, v] : b.poses_of)
    j["poses"][k] = {{"usable", v.size()}, {"dropped_outside_grid", b.rejected_of.at(k)}};
  j["throughput"] = throughput_json(b);
  j["maps"] = maps_json(b);
  j["device_limits"] = limits_json(b);
  j["roofline"] = roofline_json(b);
  j["time_split"] = b.split;
  j["targets"] = b.targets;
  j["sink"] = b.sink;  // keeps the results alive
  return j;
}

// ---------------------------------------------------------------- charts

// Latency against m' per variant (p50, p99), then the p99 of all variants.
std::vector<snapfit::Chart> latency_charts(const Bench& b, const std::string& dev_short) {
  std::vector<snapfit::Chart> charts;
  for (const auto& spec : b.specs) {
    snapfit::Chart c = make_chart("query latency vs m': " + spec.label + " (" + dev_short + ")", "retained modes m'",
                                  "latency per query (us)", true, true);
    snapfit::Series p50, p99;
    p50.label = "p50";
    p99.label = "p99";
    for (const auto& r : b.latency)
      if (r.key == spec.key) {
        p50.x.push_back(double(r.modes_used));
        p50.y.push_back(r.p50);
        p99.x.push_back(double(r.modes_used));
        p99.y.push_back(r.p99);
      }
    c.series = {p50, p99};
    c.hlines.push_back({1000.0, "1 ms"});
    if (spec.variant.translation_only) c.markers.push_back({4096.0, 1000.0, "seed 000 K20c 1 kHz (published)"});
    charts.push_back(c);
  }
  snapfit::Chart c = make_chart("query latency p99 vs m', all variants (" + dev_short + ")", "retained modes m'",
                                "p99 latency per query (us)", true, true);
  for (const auto& spec : b.specs) {
    snapfit::Series s;
    s.label = spec.label;
    for (const auto& r : b.latency)
      if (r.key == spec.key) s.x.push_back(double(r.modes_used)), s.y.push_back(r.p99);
    c.series.push_back(s);
  }
  c.hlines.push_back({1000.0, "1 ms"});
  c.markers.push_back({4096.0, 1000.0, "seed 000 K20c (published)"});
  charts.push_back(c);
  return charts;
}

snapfit::Chart throughput_chart(const Bench& b, const std::string& dev_short) {
  snapfit::Chart c = make_chart("batched throughput vs batch size (" + dev_short + ")", "poses per batch",
                                "poses per second (median batch)", true, true);
  for (const auto& spec : b.specs)
    for (std::size_t m : b.plan.batch_modes) {
      snapfit::Series s;
      s.label = spec.label + ", m' " + std::to_string(m);
      for (const auto& t : b.throughput)
        if (t.key == spec.key && t.modes == std::min(m, b.total_modes()) && !t.skipped)
          s.x.push_back(double(t.batch)), s.y.push_back(t.median_poses_per_s);
      if (!s.x.empty()) c.series.push_back(s);
    }
  c.hlines.push_back({1000.0, "1 kHz"});
  return c;
}

snapfit::Chart roofline_chart(const Bench& b) {
  const double bw = b.limits.read_gbs, peak = b.limits.peak_gflops;
  snapfit::Chart c = make_chart("roofline at m' = 32768 (measured limits; requested bytes)",
                                "arithmetic intensity (flop / byte requested)", "GFLOP/s", true, true);
  snapfit::Series roofline;
  roofline.label = "roof: min(" + fixed(peak, 0) + " GFLOP/s, " + fixed(bw, 1) + " GB/s x I)";
  roofline.style = snapfit::Series::Style::line;
  for (double x = 0.05; x <= 200.0; x *= 1.25) roofline.x.push_back(x), roofline.y.push_back(std::min(peak, bw * x));
  c.series.push_back(roofline);
  snapfit::Series single, batched;
  single.label = "single query (p50)";
  single.style = snapfit::Series::Style::points;
  batched.label = "largest batch";
  batched.style = snapfit::Series::Style::points;
  for (const auto& r : b.roof) {
    single.x.push_back(r.cost.flops / r.cost.bytes);
    single.y.push_back(r.single_gflops);
    if (r.batch_pps > 0) batched.x.push_back(r.cost.flops / r.cost.bytes), batched.y.push_back(r.batch_gflops);
    c.markers.push_back({r.cost.flops / r.cost.bytes, std::max(r.single_gflops, r.batch_gflops), r.key});
  }
  c.series.push_back(single);
  c.series.push_back(batched);
  return c;
}

std::vector<snapfit::Chart> charts(const Bench& b) {
  const std::string dev_short = b.ctx.device.info.name.substr(0, 40);
  std::vector<snapfit::Chart> out = latency_charts(b, dev_short);
  if (!b.args.latency_only) {
    out.push_back(throughput_chart(b, dev_short));
    out.push_back(roofline_chart(b));
  }
  return out;
}

// ---------------------------------------------------------------- the run

snapfit::ComputeContext open_device(const std::string& spec) {
  snapfit::ComputeContext ctx = snapfit::make_compute_context(snapfit::select_device(snapfit::device_spec_from(spec)));
  const auto& info = ctx.device.info;
  std::cout << "  device: " << snapfit::describe_device(info) << "\n  driver " << info.driver_version << ", "
            << info.compute_units << " compute units\n";
  return ctx;
}

// The scene's pair (fields from the cache or computed, with progress bars), timed.
snapfit::AssemblyPair build_pair(const Args& args, const snapfit::Scene& scene, const snapfit::ComputeContext& ctx,
                                 const snapfit::FftLibrary& fft, double& seconds) {
  snapfit::PairOptions popt;
  popt.descriptors.progress = snapfit::pass_progress_bars(std::cerr);
  const auto t0 = Clock::now();
  snapfit::AssemblyPair pair = snapfit::build_assembly_pair(scene, ctx, fft, popt);
  seconds = seconds_since(t0);
  const auto& dims = pair.spectra.dims;
  std::cout << "  pair ready in " << fixed(seconds, 1) << " s (fields "
            << (pair.fields1.from_cache ? "cached" : "computed") << " / "
            << (pair.fields2.from_cache ? "cached" : "computed") << "), FFT grid " << dims[0] << "x" << dims[1] << "x"
            << dims[2] << " = " << dims[0] * dims[1] * dims[2] << " modes, spacing " << pair.spectra.spacing << " "
            << scene.units << "\n";
  if (!snapfit::query_variant_for(scene).torque)
    throw snapfit::Error(args.scene + ": the scene asks for no torque; the benchmark needs a 6-DOF scene with torque");
  return pair;
}

void write_outputs(const Bench& b, const RunRecord& run) {
  const auto& info = b.ctx.device.info;
  const std::filesystem::path dir(b.args.out);
  std::filesystem::create_directories(dir);
  const std::string device_desc = info.name + " (" + info.platform_name + ", driver " + info.driver_version + ")";
  write_csvs(dir, b.latency, b.throughput, device_desc);
  write_json(dir / "queries.json", report_json(b, run));
  const std::string page = write_charts(dir, "bench_queries: latency and throughput", b.args.command_line, charts(b));
  std::cout << "wrote " << (dir / "queries.csv").string() << ", throughput.csv, queries.json and " << page << "\n";
}

int run(const Args& args) {
  RunRecord run;
  run.announce("bench_queries", args.command_line);
  const snapfit::FftLibrary fft;
  const snapfit::ComputeContext ctx = open_device(args.device);
  const snapfit::Scene scene = snapfit::load_scene(args.scene);
  std::cout << "  scene " << args.scene << " (" << scene.name << ")\n";
  const snapfit::AssemblyPair pair = build_pair(args, scene, ctx, fft, run.pair_s);
  run.fields_from_cache = pair.fields1.from_cache && pair.fields2.from_cache;
  Bench b(args, fft, ctx, scene, pair.spectra);

  measure_latencies(b);
  measure_throughput(b);
  b.engines.clear();
  measure_maps(b);
  measure_roofline(b);
  time_split(b);
  check_targets(b);

  run.stop();
  for (const auto& r : b.latency) run.others_latency_max = std::max(run.others_latency_max, r.other_cores);
  std::cout << run.end_text() << "other processes kept " << fixed(run.others_run, 2)
            << " cores busy on average (at most " << fixed(run.others_latency_max, 2) << " during a latency point); "
            << b.guard.retries << " points re-measured after waiting " << fixed(b.guard.waited_s, 0) << " s\n";
  write_outputs(b, run);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  snapfit::expose_pocl_caller_thread_driver();  // --device basic: the haptic loop's device
  return guarded_main("bench_queries", [&] { return run(parse_args(argc, argv)); });
}
