// The energy split as Ewald summation splits a sum (engine/query/near_field.h): what it
// costs and what it buys. Per pose along the trajectory, in double on the host:
//   - the per-mode terms of the exact-rotation product over every mode
//     (perf/product_modes.h), which give the reference E, F, T, the split's exact near
//     part sum_k (1 - G) W_k e^{i phi_k} and its far part's truncation at each m';
//   - the near part in space (near_wrench), its time on one thread and its error against
//     its own modes;
//   - the split, far part truncated at m' plus near part in space, against the reference.
// Error over the poses as scheduler/tuning/accuracy.h: sqrt(sum |x - ref|^2 / sum |ref|^2).
//
//   bench_near_far --help lists its options.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <complex>
#include <filesystem>
#include <iostream>
#include <numeric>

#include "engine/query/near_field.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "perf/product_modes.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/tuning/accuracy.h"

using namespace snapfit;
using Cd = std::complex<double>;

namespace {

struct Wrench {
  double e = 0;
  Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
  Wrench& operator+=(const Wrench& o) {
    e += o.e, f += o.f, t += o.t;
    return *this;
  }
};

struct ErrorSums {
  double d[3] = {0, 0, 0}, r[3] = {0, 0, 0};
  void add(const Wrench& x, const Wrench& ref) {
    d[0] += (x.e - ref.e) * (x.e - ref.e), d[1] += (x.f - ref.f).squaredNorm(), d[2] += (x.t - ref.t).squaredNorm();
    r[0] += ref.e * ref.e, r[1] += ref.f.squaredNorm(), r[2] += ref.t.squaredNorm();
  }
  double rel(int i) const { return std::sqrt(d[i] / std::max(r[i], 1e-300)); }
};

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_near_far", [&] {
    bool quick = false;
    std::string device_spec, out_dir = "results/bench_near_far", scene_path = "scenes/default.json";
    long pose_count = 8;
    std::vector<double> widths{1.0, 1.5, 2.0, 3.0};  // a, in grid spacings
    std::vector<int> kernel_widths{4, 5};
    double margin = NearFieldOptions{}.margin_widths;
    int rotation_width = SpectrumOptions{}.exact_rotation_width;
    CLI::App app{
        "The energy split as Ewald summation splits a sum: a smooth far part at m' modes, an exact near part "
        "in space",
        "bench_near_far"};
    bench::add_common_options(app, quick, device_spec, out_dir, "2 poses, a = 2 spacings, kernel width 5");
    app.add_option("--scene", scene_path, "scene");
    app.add_option("--poses", pose_count, "poses along the trajectory")->check(CLI::Range(1, 10000));
    app.add_option("--widths", widths, "Gaussian widths a, in grid spacings");
    app.add_option("--kernel-widths", kernel_widths, "the near part's kernel widths (taps per axis)");
    app.add_option("--rotation-width", rotation_width,
                   "the exact rotation's kernel width (the reference's part 2 spectrum: 5 ~1e-4, 7 ~1e-6)")
        ->check(CLI::Range(2, 15));
    app.add_option("--margin", margin, "fine nodes kept beyond part 1's samples, in widths a (100: the whole box)")
        ->check(CLI::PositiveNumber);
    bench::parse(app, argc, argv);
    if (quick) pose_count = 2, widths = {2.0}, kernel_widths = {5};
    const std::string load_start = bench::read_loadavg();
    const Scene scene = load_scene(scene_path);
    if (scene.motion == Motion::translation) throw Error("bench_near_far: the scene must be 6-DOF");
    const Device device = select_device(device_spec_from(device_spec));
    const FftLibrary fft;
    const ComputeContext ctx = make_compute_context(device);
    PairOptions pair_options;
    pair_options.spectrum.exact_rotation_width = rotation_width;
    const AssemblyPair pair = build_assembly_pair(scene, ctx, fft, pair_options);
    const PairSpectra& sp = pair.spectra;
    const std::vector<Pose> poses = accuracy_poses(scene, std::size_t(pose_count));
    const GridSpec& grid2 = pair.fields2.fields.grid;
    std::vector<Complex> rho2;
    for (float v : affinity_imaginary(pair.fields2.fields)) rho2.emplace_back(0.0f, v);

    bench::ProductModes product(ctx, sp);
    const std::size_t M = product.size();
    const std::vector<Eigen::Vector3d>& w = product.frequencies();
    std::vector<std::size_t> levels;
    for (std::size_t m = 4096; m <= 131072 && m < M; m *= 2) levels.push_back(m);
    std::cout << "scene " << scene_path << ": FFT box " << sp.dims[0] << " x " << sp.dims[1] << " x " << sp.dims[2]
              << " (" << M << " modes), h " << sp.spacing << ", part 2 samples " << rho2.size() << "\n";

    // Per pose: every mode's term (the reference and the split's exact parts).
    std::vector<std::vector<Wrench>> terms(poses.size());
    std::vector<Wrench> reference(poses.size());
    std::vector<bench::ModeTerm> modes;
    for (std::size_t p = 0; p < poses.size(); ++p) {
      product.terms(poses[p], modes);
      for (const bench::ModeTerm& m : modes) {
        terms[p].push_back(Wrench{m.e, m.f, m.t});
        reference[p] += terms[p].back();
      }
      std::cerr << "\rreference pose " << p + 1 << "/" << poses.size() << std::flush;
    }
    std::cerr << "\n";
    nlohmann::json rows = nlohmann::json::array();
    std::cout << "\n| a (h) | m' | far truncation E / F / T | kernel width | samples evaluated (median) | "
                 "near ms (1 thread, median) | near vs its modes E / F / T | split E / F / T | split, far part "
                 "tricubic E / F / T |\n"
              << "|---|---|---|---|---|---|---|---|---|\n";
    for (double a_h : widths) {
      const double a = a_h * sp.spacing;
      // The split's exact parts per pose: near over every mode, far truncated per m'.
      std::vector<double> gk(M);
      for (std::size_t i = 0; i < M; ++i) gk[i] = std::exp(-2 * M_PI * M_PI * a * a * w[i].squaredNorm());
      std::vector<Wrench> near_modes(poses.size()), far_all(poses.size());
      std::vector<std::vector<Wrench>> far_at(poses.size(), std::vector<Wrench>(levels.size()));
      for (std::size_t p = 0; p < poses.size(); ++p) {
        Wrench far;
        std::size_t lv = 0;
        for (std::size_t i = 0; i < M; ++i) {
          const Wrench& t = terms[p][i];
          far.e += gk[i] * t.e, far.f += gk[i] * t.f, far.t += gk[i] * t.t;
          if (lv < levels.size() && i + 1 == levels[lv]) far_at[p][lv++] = far;
        }
        far_all[p] = far;
        near_modes[p].e = reference[p].e - far.e, near_modes[p].f = reference[p].f - far.f,
        near_modes[p].t = reference[p].t - far.t;
      }
      for (int kw : kernel_widths) {
        NearFieldOptions options;
        options.width_spacings = a_h;
        options.kernel_width = kw;
        options.margin_widths = margin;
        const NearField near_field = build_near_field(fft, ctx, sp, grid2, rho2, options);
        std::cerr << "a " << a_h << " h, kernel width " << kw << ": " << near_field.dims[0] << " x "
                  << near_field.dims[1] << " x " << near_field.dims[2] << " fine nodes, " << near_field.samples.size()
                  << " samples of part 2, " << near_field.bytes() / 1e6 << " MB, built in " << near_field.seconds
                  << " s\n";
        {
          std::vector<Wrench> near(poses.size());
          std::vector<double> ms, counts;
          ErrorSums near_err;
          for (std::size_t p = 0; p < poses.size(); ++p) {
            const auto t1 = std::chrono::steady_clock::now();
            const NearWrench n = near_wrench(near_field, poses[p]);
            ms.push_back(1e3 * bench::seconds_since(t1));
            counts.push_back(double(n.samples));
            near[p].e = n.energy, near[p].f = n.force, near[p].t = n.torque;
            near_err.add(near[p], near_modes[p]);
          }
          // The far part as the loop would sum it: tricubic interpolation of part 2's spectrum.
          const PairSpectra far_sp = far_spectra(sp, near_field);
          auto tricubic = make_query_engine(ctx, far_sp, query_variant_for(scene, Interpolation::tricubic));
          for (std::size_t lv = 0; lv < levels.size(); ++lv) {
            ErrorSums trunc, split, split_tricubic;
            tricubic->set_modes(levels[lv]);
            for (std::size_t p = 0; p < poses.size(); ++p) {
              Wrench total = far_at[p][lv];
              trunc.add(total, far_all[p]);
              total += near[p];
              split.add(total, reference[p]);
              const QueryResult q = tricubic->query(poses[p]);
              Wrench interpolated{q.energy, q.force, q.torque};
              interpolated += near[p];
              split_tricubic.add(interpolated, reference[p]);
            }
            // The far part's truncation relative to the reference's size, not its own.
            for (int q = 0; q < 3; ++q) trunc.r[q] = split.r[q];
            std::cout << "| " << a_h << " | " << levels[lv] << " | " << bench::fixed(100 * trunc.rel(0), 2) << " / "
                      << bench::fixed(100 * trunc.rel(1), 2) << " / " << bench::fixed(100 * trunc.rel(2), 2) << " % | "
                      << kw << " | " << bench::median(counts) << " | " << bench::fixed(bench::median(ms), 2) << " | "
                      << bench::fixed(100 * near_err.rel(0), 3) << " / " << bench::fixed(100 * near_err.rel(1), 3)
                      << " / " << bench::fixed(100 * near_err.rel(2), 3) << " % | "
                      << bench::fixed(100 * split.rel(0), 2) << " / " << bench::fixed(100 * split.rel(1), 2) << " / "
                      << bench::fixed(100 * split.rel(2), 2) << " % | " << bench::fixed(100 * split_tricubic.rel(0), 2)
                      << " / " << bench::fixed(100 * split_tricubic.rel(1), 2) << " / "
                      << bench::fixed(100 * split_tricubic.rel(2), 2) << " % |\n";
            rows.push_back(
                {{"a_spacings", a_h},
                 {"modes", levels[lv]},
                 {"kernel_width", kw},
                 {"build_seconds", near_field.seconds},
                 {"samples_evaluated_median", bench::median(counts)},
                 {"near_ms_median", bench::median(ms)},
                 {"near_error", {near_err.rel(0), near_err.rel(1), near_err.rel(2)}},
                 {"far_truncation", {trunc.rel(0), trunc.rel(1), trunc.rel(2)}},
                 {"split_error", {split.rel(0), split.rel(1), split.rel(2)}},
                 {"split_tricubic_error", {split_tricubic.rel(0), split_tricubic.rel(1), split_tricubic.rel(2)}}});
          }
        }
      }
    }
    std::filesystem::create_directories(out_dir);
    nlohmann::json summary = bench::run_record(argc, argv, describe_device(device.info), load_start);
    summary["scene"] = scene_path;
    summary["poses"] = poses.size();
    summary["rows"] = rows;
    bench::write_json(std::filesystem::path(out_dir) / "summary.json", summary);
    return 0;
  });
}
