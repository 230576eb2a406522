// The energy split as Ewald summation splits a sum (engine/query/near_field.h): what it
// costs and what it buys. Per pose along the trajectory, in double on the host:
//   - the per-mode terms of the exact-rotation product over every mode
//     (perf/product_modes.h), which give the reference E, F, T, the split's exact near
//     part sum_k (1 - G) W_k e^{i phi_k} and its far part's truncation at each m';
//   - the near part in space (near_wrench), its time on one thread and its error against
//     its own modes; at the poses where part 2 reaches beyond its kept nodes, whether the
//     bound on what they leave out (NearWrench::left_out) covers that error;
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

// Every mode's term at each pose, and their sum (the reference), with progress.
void mode_terms(bench::ProductModes& product, const std::vector<Pose>& poses, std::vector<std::vector<Wrench>>& terms,
                std::vector<Wrench>& reference) {
  terms.assign(poses.size(), {});
  reference.assign(poses.size(), Wrench{});
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
}

// The split's exact parts per pose, from every mode's term: the far part (each term
// times the Gaussian's exp(-2 pi^2 a^2 |w|^2)) over every mode and over the first m' of
// each level, and the near part over every mode (the reference less the far part).
struct SplitByModes {
  std::vector<Wrench> near, far;
  std::vector<std::vector<Wrench>> far_at;  // [pose][level]
};

SplitByModes split_by_modes(const std::vector<std::vector<Wrench>>& terms, const std::vector<Wrench>& reference,
                            const std::vector<Eigen::Vector3d>& w, double a, const std::vector<std::size_t>& levels) {
  const std::size_t M = w.size(), poses = terms.size();
  std::vector<double> gk(M);
  for (std::size_t i = 0; i < M; ++i) gk[i] = std::exp(-2 * M_PI * M_PI * a * a * w[i].squaredNorm());
  SplitByModes out{std::vector<Wrench>(poses), std::vector<Wrench>(poses),
                   std::vector<std::vector<Wrench>>(poses, std::vector<Wrench>(levels.size()))};
  for (std::size_t p = 0; p < poses; ++p) {
    Wrench far;
    std::size_t lv = 0;
    for (std::size_t i = 0; i < M; ++i) {
      const Wrench& t = terms[p][i];
      far.e += gk[i] * t.e, far.f += gk[i] * t.f, far.t += gk[i] * t.t;
      if (lv < levels.size() && i + 1 == levels[lv]) out.far_at[p][lv++] = far;
    }
    out.far[p] = far;
    out.near[p].e = reference[p].e - far.e, out.near[p].f = reference[p].f - far.f,
    out.near[p].t = reference[p].t - far.t;
  }
  return out;
}

// The poses at which part 2 reached beyond the near field's kept nodes, and at how many
// of them NearWrench::left_out covered the near part's error (E, F, T).
struct LeftOutCover {
  std::size_t poses = 0, covered[3] = {0, 0, 0};
  std::string text() const {
    if (poses == 0) return "none";
    return std::to_string(covered[0]) + " / " + std::to_string(covered[1]) + " / " + std::to_string(covered[2]) +
           " of " + std::to_string(poses);
  }
};

// The near part in space at each pose: its values, time, samples evaluated, error
// against its own modes, and where part 2 reaches beyond the kept nodes whether the
// left-out bound covers that error.
struct NearAtPoses {
  std::vector<Wrench> near;
  std::vector<double> ms, counts;
  ErrorSums error;
  LeftOutCover beyond;
};

NearAtPoses near_at_poses(const NearField& field, const std::vector<Pose>& poses,
                          const std::vector<Wrench>& near_modes) {
  NearAtPoses out;
  out.near.resize(poses.size());
  for (std::size_t p = 0; p < poses.size(); ++p) {
    const auto t1 = std::chrono::steady_clock::now();
    const NearWrench n = near_wrench(field, poses[p]);
    out.ms.push_back(1e3 * seconds_since(t1));
    out.counts.push_back(double(n.samples));
    Wrench& x = out.near[p];
    x.e = n.energy, x.f = n.force, x.t = n.torque;
    out.error.add(x, near_modes[p]);
    if (n.left_out.energy > 0) {
      ++out.beyond.poses;
      out.beyond.covered[0] += std::abs(x.e - near_modes[p].e) <= n.left_out.energy;
      out.beyond.covered[1] += (x.f - near_modes[p].f).norm() <= n.left_out.force;
      out.beyond.covered[2] += (x.t - near_modes[p].t).norm() <= n.left_out.torque;
    }
  }
  return out;
}

// One row's settings and costs.
struct RowSetting {
  double a_spacings;
  std::size_t modes;
  int kernel_width;
  double build_seconds, samples_median, near_ms_median;
};

// Prints one row of the table and returns it as JSON.
nlohmann::json report_row(const RowSetting& r, const LeftOutCover& beyond, const ErrorSums& trunc,
                          const ErrorSums& near_err,
                          const ErrorSums& split, const ErrorSums& split_tricubic) {
  const auto percent = [](const ErrorSums& e, int digits) {
    return bench::fixed(100 * e.rel(0), digits) + " / " + bench::fixed(100 * e.rel(1), digits) + " / " +
           bench::fixed(100 * e.rel(2), digits) + " %";
  };
  std::cout << "| " << r.a_spacings << " | " << r.modes << " | " << percent(trunc, 2) << " | " << r.kernel_width
            << " | " << r.samples_median << " | " << bench::fixed(r.near_ms_median, 2) << " | " << percent(near_err, 3)
            << " | " << beyond.text()
            << " | " << percent(split, 2) << " | " << percent(split_tricubic, 2) << " |\n";
  const auto rel = [](const ErrorSums& e) { return nlohmann::json{e.rel(0), e.rel(1), e.rel(2)}; };
  return {{"a_spacings", r.a_spacings},
          {"modes", r.modes},
          {"kernel_width", r.kernel_width},
          {"build_seconds", r.build_seconds},
          {"samples_evaluated_median", r.samples_median},
          {"near_ms_median", r.near_ms_median},
          {"near_error", rel(near_err)},
          {"poses_beyond_kept_nodes", beyond.poses},
          {"left_out_bound_covers", {beyond.covered[0], beyond.covered[1], beyond.covered[2]}},
          {"far_truncation", rel(trunc)},
          {"split_error", rel(split)},
          {"split_tricubic_error", rel(split_tricubic)}};
}

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
    bool no_reach = false;
    app.add_flag("--no-reach", no_reach,
                 "keep part 1's samples and --margin beyond them, not the region part 2 can reach");
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
    std::vector<std::vector<Wrench>> terms;
    std::vector<Wrench> reference;
    mode_terms(product, poses, terms, reference);
    nlohmann::json rows = nlohmann::json::array();
    std::cout << "\n| a (h) | m' | far truncation E / F / T | kernel width | samples evaluated (median) | "
                 "near ms (1 thread, median) | near vs its modes E / F / T | poses beyond the kept nodes: left-out "
                 "bound covers E / F / T | split E / F / T | split, far part tricubic E / F / T |\n"
              << "|---|---|---|---|---|---|---|---|---|---|\n";
    for (double a_h : widths) {
      const double a = a_h * sp.spacing;
      const SplitByModes by_modes = split_by_modes(terms, reference, w, a, levels);
      const std::vector<Wrench>&near_modes = by_modes.near, &far_all = by_modes.far;
      const std::vector<std::vector<Wrench>>& far_at = by_modes.far_at;
      for (int kw : kernel_widths) {
        NearFieldOptions options;
        options.width_spacings = a_h;
        options.kernel_width = kw;
        options.margin_widths = margin;
        if (!no_reach && pair.region.box_known) options.reach = pair.region.box;
        const NearField near_field = build_near_field(fft, ctx, sp, grid2, rho2, options);
        std::cerr << "a " << a_h << " h, kernel width " << kw << ": " << near_field.dims[0] << " x "
                  << near_field.dims[1] << " x " << near_field.dims[2] << " fine nodes, " << near_field.samples.size()
                  << " samples of part 2, " << near_field.bytes() / 1e6 << " MB, built in " << near_field.seconds
                  << " s\n";
        {
          const NearAtPoses at = near_at_poses(near_field, poses, near_modes);
          const std::vector<Wrench>& near = at.near;
          const std::vector<double>&ms = at.ms, &counts = at.counts;
          const ErrorSums& near_err = at.error;
          const LeftOutCover& beyond = at.beyond;
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
            rows.push_back(
                report_row({a_h, levels[lv], kw, near_field.seconds, bench::median(counts), bench::median(ms)}, beyond,
                           trunc, near_err, split, split_tricubic));
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
