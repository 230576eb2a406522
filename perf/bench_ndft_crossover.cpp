// Where the type-1 NUFFT of a ball set overtakes the direct NDFT on this device
// (engine/spectra/ball_spectrum.h), the measurement behind the pipeline's "auto" method
// (pipeline/sphere_spectra.h ball_spectrum_method).
//
//   bench_ndft_crossover --help lists its options.
//
// Balls: seed 001 Algorithm 1 on the hole block of scenes/default.json at tolerance 0.5
// (--quick: 1), the first k of them for k = 16, 32, ... (beyond the decomposition's count,
// the set again shifted by a fixed offset per copy, so the radii stay the part's). Lattices:
// n^3 nodes of spacing 1 / (n h) with the scene's h = 0.6 (the same largest |w|, so the
// same NUFFT radius nodes), n = 32, 48, 64, 96 (--quick: 24, 32). Each method once to
// build its programs and plans, then the median of 3 runs (--quick: 1) of the whole
// evaluation with its uploads and downloads. A lattice stops growing k after the first
// direct run over 5 s. Per lattice: the smallest k at which the
// NUFFT is faster, and the ball-mode pairs k n^3 there.
// Output in DIR (default results/bench_ndft_crossover): crossover.csv (per lattice and k),
// crossover.json, charts.html.
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/quantile.h"
#include "engine/fields/sphere_decomposition.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/spectra/ball_spectrum.h"
#include "engine/spectra/fft3d.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "pipeline/assembly_pair.h"
#include "pipeline/sphere_spectra.h"
#include "snapfit/scene.h"

namespace {

namespace fs = std::filesystem;
using namespace snapfit;
using namespace snapfit::bench;  // perf/bench_common.h: tables, CSV, JSON

// The median (nearest rank) of `runs` timed calls of f.
template <class F>
double median_seconds(int runs, F f) {
  std::vector<double> s;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    s.push_back(seconds_since(t0));
  }
  return quantile(s, 0.5);
}

std::vector<Ball> first_balls(const std::vector<Ball>& balls, std::size_t k) {
  std::vector<Ball> out;
  for (std::size_t i = 0; i < k; ++i) {
    Ball b = balls[i % balls.size()];
    b.centre += double(i / balls.size()) * Eigen::Vector3d(0.37, 0.21, 0.13);
    out.push_back(b);
  }
  return out;
}

struct Point {
  std::size_t n = 0, balls = 0;
  double direct_s = NAN, nufft_s = NAN;
};

int run(int argc, char** argv) {
  bool quick = false;
  std::string device, out = "results/bench_ndft_crossover";
  CLI::App app{"Direct NDFT against type-1 NUFFT of ball spectra over ball counts and lattice sizes.",
               "bench_ndft_crossover"};
  add_common_options(app, quick, device, out);
  parse(app, argc, argv);
  const std::string load_start = read_loadavg();
  std::cout << "bench_ndft_crossover: " << command_line(argc, argv) << "\n  date " << now_iso()
            << ", load average at start: " << load_start << "\n";
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(select_device(device_spec_from(device)));
  std::cout << "  device: " << describe_device(ctx.device.info) << "\n";

  const Scene scene = load_scene("scenes/default.json");
  const AssemblyPair pair = prepare_assembly_pair(scene);
  SphereDecompositionParams params;
  params.tolerance = quick ? 1.0 : 0.5;
  DescriptorOptions quiet;
  const SphereDecomposition d = decompose_part(ctx, pair.parts.part1.mesh, scene.descriptor, params, quiet);
  std::cout << "  balls: " << d.balls.size() << " (hole block, tolerance " << params.tolerance << ")\n";

  Eigen::AlignedBox3d box;
  for (const Ball& b : d.balls) box.extend(b.centre);
  const Eigen::Vector3d centre = box.center();
  const double h = 0.6;
  const std::vector<std::size_t> sizes =
      quick ? std::vector<std::size_t>{24, 32} : std::vector<std::size_t>{32, 48, 64, 96};
  const std::size_t max_balls = quick ? 1024 : 8192;
  const int runs = quick ? 1 : 3;
  const double direct_cap_s = 5.0;
  std::vector<Point> points;
  nlohmann::json crossings = nlohmann::json::array();
  for (std::size_t n : sizes) {
    FrequencyLattice lattice;
    lattice.dims = {n, n, n};
    lattice.length = Eigen::Vector3d::Constant(double(n) * h);
    lattice.centre = centre;
    // Programs and plans first, outside the timings.
    ball_spectrum_direct(ctx, first_balls(d.balls, 16), lattice);
    ball_spectrum_nufft(fft, ctx, first_balls(d.balls, 16), lattice);
    bool direct_capped = false;
    std::size_t crossing = 0;
    for (std::size_t k = 16; k <= max_balls; k *= 2) {
      const std::vector<Ball> balls = first_balls(d.balls, k);
      Point p{n, k};
      if (!direct_capped) p.direct_s = median_seconds(runs, [&] { ball_spectrum_direct(ctx, balls, lattice); });
      direct_capped = direct_capped || p.direct_s > direct_cap_s;
      p.nufft_s = median_seconds(runs, [&] { ball_spectrum_nufft(fft, ctx, balls, lattice); });
      if (crossing == 0 && std::isfinite(p.direct_s) && p.nufft_s < p.direct_s) crossing = k;
      std::cout << "  lattice " << pad(std::to_string(n), 3) << "^3  balls " << pad(std::to_string(k), 6) << "  direct "
                << pad(std::isfinite(p.direct_s) ? fixed(p.direct_s * 1e3, 1) : "-", 9) << " ms  nufft "
                << pad(fixed(p.nufft_s * 1e3, 1), 9) << " ms\n"
                << std::flush;
      points.push_back(p);
      if (direct_capped) break;  // past the direct sum's last run: nothing left to compare
    }
    const double pairs = double(crossing) * double(n * n * n);
    std::cout << "  lattice " << n << "^3: NUFFT faster from " << (crossing ? std::to_string(crossing) : "-")
              << " balls (" << (crossing ? fixed(pairs / 1e6, 1) + "e6 ball-mode pairs" : "not within the range")
              << "); the pipeline's auto picks "
              << (crossing ? ball_spectrum_method("auto", crossing, n * n * n) : std::string("-")) << " there\n";
    crossings.push_back({{"n", n}, {"modes", n * n * n}, {"crossing_balls", crossing}, {"crossing_pairs", pairs}});
  }

  fs::create_directories(out);
  CsvFile csv(fs::path(out) / "crossover.csv", "n,modes,balls,direct_s,nufft_s");
  nlohmann::json jpoints = nlohmann::json::array();
  for (const Point& p : points) {
    csv.row(p.n, p.n * p.n * p.n, p.balls, p.direct_s, p.nufft_s);
    jpoints.push_back({{"n", p.n}, {"balls", p.balls}, {"direct_s", num(p.direct_s)}, {"nufft_s", num(p.nufft_s)}});
  }
  nlohmann::json report = run_record(argc, argv, describe_device(ctx.device.info), load_start);
  report["points"] = jpoints;
  report["crossings"] = crossings;
  write_json(fs::path(out) / "crossover.json", report);
  Chart chart = make_chart("Ball spectrum onto n^3 modes: direct NDFT and NUFFT against the ball count", "balls",
                           "seconds", true, true);
  for (std::size_t n : sizes)
    for (const std::string method : {"direct", "nufft"}) {
      Series s{method + " " + std::to_string(n) + "^3", {}, {}, Series::Style::line_points, ""};
      for (const Point& p : points) {
        const double t = method == "direct" ? p.direct_s : p.nufft_s;
        if (p.n == n && std::isfinite(t)) s.x.push_back(double(p.balls)), s.y.push_back(t);
      }
      chart.series.push_back(s);
    }
  const std::string page =
      write_charts(out, "bench_ndft_crossover: direct NDFT against NUFFT", command_line(argc, argv), {chart});
  std::cout << "wrote " << out << "/crossover.csv, crossover.json and " << page << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return snapfit::bench::guarded_main("bench_ndft_crossover", [&] { return run(argc, argv); });
}
