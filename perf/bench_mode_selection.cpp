// Which m' modes to keep: the truncation error of E, F and T when the retained modes of
// the exact-rotation product (engine/query/rotated_product.h) are the lowest |w| (the engine's
// mode order, a low-pass ball) or the largest per-mode weights. At each pose along the
// scene's trajectory the product is made for the pose's own rotation over every mode and
// read back; then, in double on the host, each mode's term (perf/product_modes.h),
// summed over each selection at each m'. Selections: "lowest frequency" (lowest |w|);
// "largest product" (largest |W_k|: the energy's error is at most the sum of the dropped
// |W_k|); "largest torque weight" (largest |G_k|, the same for the torque); "largest
// normalised sum" (|W|, |w||W| and |G|, each divided by its sum over the modes). The reference is the
// sum over every mode, checked against the engine's own all-mode query at each pose.
// Error over the poses as scheduler/tuning/accuracy.h: sqrt(sum |x - ref|^2 / sum |ref|^2).
//
//   bench_mode_selection --help lists its options.
#include <algorithm>
#include <cmath>
#include <complex>
#include <filesystem>
#include <iostream>
#include <numeric>

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

struct Terms {
  std::vector<double> e;
  std::vector<Eigen::Vector3d> f, t;
};

// Per-mode score of each selection but the first (which keeps the mode order).
constexpr int kSelections = 4;
const char* const kSelectionNames[kSelections] = {"lowest frequency", "largest product", "largest torque weight",
                                                  "largest normalised sum"};

// Each mode's term into `terms`, their sums E, F, T, and each mode's score for the
// selections after the first.
void mode_terms(const std::vector<bench::ModeTerm>& modes, const std::vector<Eigen::Vector3d>& w, Terms& terms,
                std::vector<double> (&score)[kSelections], double& E, Eigen::Vector3d& F, Eigen::Vector3d& T) {
  double sums[3] = {0, 0, 0};
  const std::size_t M = modes.size();
  for (std::size_t i = 0; i < M; ++i) {
    const bench::ModeTerm& m = modes[i];
    terms.e[i] = m.e, terms.f[i] = m.f, terms.t[i] = m.t;
    E += m.e, F += m.f, T += m.t;
    score[1][i] = std::abs(m.W);
    score[2][i] = std::sqrt(std::norm(m.G[0]) + std::norm(m.G[1]) + std::norm(m.G[2]));
    score[3][i] = std::abs(m.W) * w[i].norm();  // the force's weight, for the sum below
    sums[0] += score[1][i], sums[1] += score[2][i], sums[2] += score[3][i];
  }
  for (std::size_t i = 0; i < M; ++i)
    score[3][i] = score[1][i] / sums[0] + score[2][i] / sums[1] + score[3][i] / sums[2];
}

// Adds each selection's squared error against the full sums (E, F, T) at each m' of
// `levels` to dE, dF, dT (index selection * levels + level); `idx` is scratch.
void add_selection_errors(const Terms& terms, const std::vector<double> (&score)[kSelections],
                          const std::vector<std::size_t>& levels, double E, const Eigen::Vector3d& F,
                          const Eigen::Vector3d& T, std::vector<std::uint32_t>& idx, std::vector<double>& dE,
                          std::vector<double>& dF, std::vector<double>& dT) {
  const std::size_t L = levels.size();
  for (int s = 0; s < kSelections; ++s) {
    std::iota(idx.begin(), idx.end(), 0u);
    if (s > 0) {
      const std::vector<double>& sc = score[s];
      std::partial_sort(idx.begin(), idx.begin() + levels.back(), idx.end(),
                        [&](std::uint32_t a, std::uint32_t b) { return sc[a] > sc[b]; });
    }
    double e = 0;
    Eigen::Vector3d f = Eigen::Vector3d::Zero(), t = Eigen::Vector3d::Zero();
    std::size_t done = 0;
    for (std::size_t j = 0; j < L; ++j) {
      for (; done < levels[j]; ++done) e += terms.e[idx[done]], f += terms.f[idx[done]], t += terms.t[idx[done]];
      dE[s * L + j] += (e - E) * (e - E);
      dF[s * L + j] += (f - F).squaredNorm();
      dT[s * L + j] += (t - T).squaredNorm();
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_mode_selection", [&] {
    bool quick = false;
    std::string device_spec, out_dir = "results/bench_mode_selection", scene_path = "scenes/default.json";
    long pose_count = 12;
    CLI::App app{
        "Which m' modes to keep: the truncation error of E, F and T per mode selection of the exact-rotation product",
        "bench_mode_selection"};
    bench::add_common_options(app, quick, device_spec, out_dir, "2 poses, m' up to 16,384");
    app.add_option("--scene", scene_path, "scene");
    app.add_option("--poses", pose_count, "poses along the trajectory")->check(CLI::Range(1, 10000));
    bench::parse(app, argc, argv);
    if (quick) pose_count = 2;
    const std::string load_start = bench::read_loadavg();
    const Scene scene = load_scene(scene_path);
    if (scene.motion == Motion::translation) throw Error("bench_mode_selection: the scene must be 6-DOF");
    const Device device = select_device(device_spec_from(device_spec));
    const FftLibrary fft;
    const ComputeContext ctx = make_compute_context(device);
    const AssemblyPair pair = build_assembly_pair(scene, ctx, fft);
    const PairSpectra& sp = pair.spectra;
    const std::vector<Pose> poses = accuracy_poses(scene, std::size_t(pose_count));

    bench::ProductModes product(ctx, sp);
    const std::size_t M = product.size();
    std::vector<std::size_t> levels;
    for (std::size_t m = 4096; m <= (quick ? 16384u : 262144u) && m < M; m *= 2) levels.push_back(m);
    std::vector<bench::ModeTerm> modes;

    // The engine's all-mode exact query, to check the host sums against.
    auto engine = make_query_engine(
        ctx, sp, bench::exact_reference_variant(query_variant_for(scene, Interpolation::tricubic), M));
    engine->set_modes(engine->max_modes());

    const std::size_t L = levels.size();
    std::vector<double> dE(kSelections * L), dF(kSelections * L), dT(kSelections * L);
    double rE = 0, rF = 0, rT = 0;
    double largest_diff[3] = {0, 0, 0}, scale[3] = {0, 0, 0};  // host against engine, per output
    Terms terms{std::vector<double>(M), std::vector<Eigen::Vector3d>(M), std::vector<Eigen::Vector3d>(M)};
    std::vector<double> score[kSelections];
    for (auto& s : score) s.resize(M);
    std::vector<std::uint32_t> idx(M);
    for (std::size_t p = 0; p < poses.size(); ++p) {
      product.terms(poses[p], modes);
      double E = 0;
      Eigen::Vector3d F = Eigen::Vector3d::Zero(), T = Eigen::Vector3d::Zero();
      mode_terms(modes, product.frequencies(), terms, score, E, F, T);
      const QueryResult ref = engine->query(poses[p]);
      const double diff[3] = {std::abs(ref.energy - E), (ref.force - F).norm(), (ref.torque - T).norm()},
                   size[3] = {std::abs(E), F.norm(), T.norm()};
      for (int q = 0; q < 3; ++q)
        largest_diff[q] = std::max(largest_diff[q], diff[q]), scale[q] = std::max(scale[q], size[q]);
      rE += E * E, rF += F.squaredNorm(), rT += T.squaredNorm();
      add_selection_errors(terms, score, levels, E, F, T, idx, dE, dF, dT);
      std::cerr << "\rpose " << p + 1 << "/" << poses.size() << std::flush;
    }
    std::cerr << "\n";
    // Against each output's largest size over the poses (a torque that cancels at one pose
    // differs there by float rounding of the terms of the others' size).
    double check = 0;
    for (int q = 0; q < 3; ++q) check = std::max(check, largest_diff[q] / std::max(scale[q], 1e-30));

    std::filesystem::create_directories(out_dir);
    bench::CsvFile csv(std::filesystem::path(out_dir) / "mode_selection.csv",
                       "selection,modes,energy_error,force_error,torque_error");
    nlohmann::json rows = nlohmann::json::array();
    std::cout
        << "scene " << scene_path << ", " << poses.size() << " poses, " << M
        << " modes in all; relative error against the sum over every mode\n"
        << "host sums against the engine's all-mode query: largest difference, relative to the output's largest size, "
        << check << "\n\n"
        << "| selection | m' | energy | force | torque |\n|---|---|---|---|---|\n";
    for (int s = 0; s < kSelections; ++s)
      for (std::size_t j = 0; j < L; ++j) {
        const double e = std::sqrt(dE[s * L + j] / rE), f = std::sqrt(dF[s * L + j] / rF),
                     t = std::sqrt(dT[s * L + j] / rT);
        csv.row(bench::quoted(kSelectionNames[s]), levels[j], e, f, t);
        rows.push_back({{"selection", kSelectionNames[s]},
                        {"modes", levels[j]},
                        {"energy_error", e},
                        {"force_error", f},
                        {"torque_error", t}});
        std::cout << "| " << kSelectionNames[s] << " | " << levels[j] << " | " << bench::fixed(100 * e, 2) << " % | "
                  << bench::fixed(100 * f, 2) << " % | " << bench::fixed(100 * t, 2) << " % |\n";
      }
    nlohmann::json summary = bench::run_record(argc, argv, describe_device(device.info), load_start);
    summary["scene"] = scene_path;
    summary["poses"] = poses.size();
    summary["modes_total"] = M;
    summary["host_vs_engine_max_relative_difference"] = check;
    summary["rows"] = rows;
    bench::write_json(std::filesystem::path(out_dir) / "summary.json", summary);
    std::cout << "\nwrote " << out_dir << "/mode_selection.csv and summary.json\n";
    // The host sums must reproduce the engine's: a float kernel against double sums.
    return check < 1e-3 ? 0 : 1;
  });
}
