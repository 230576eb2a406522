// How the per-query error estimate (engine/query/error_estimate.h) relates to the true error:
// at poses along a scene's trajectory, for the loop's strategy (tricubic interpolation, or
// the translation lines) at several m', the true error of E, |F| and |T| against the
// exact reference (every mode, exact rotation: scheduler/tuning/accuracy.h) divided by the root
// sum of squares of the two band sums (the estimate before kErrorEstimateScale). Its
// quantiles are what the scale is chosen from (the 95th percentile: the estimate covers
// the error at 95 % of poses); the coverage and the median estimate / error at the
// shipped scale say how the estimate does.
//
//   bench_error_estimate --help lists its options.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "core/quantile.h"
#include "engine/query/error_estimate.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/tuning/accuracy.h"
#include "scheduler/tuning/engine_tuning.h"

using namespace snapfit;

int main(int argc, char** argv) {
  return bench::guarded_main("bench_error_estimate", [&] {
    bool quick = false;
    std::string device_spec, out_dir = "results/bench_error_estimate", scene_path = "scenes/default.json";
    long pose_count = 40;
    CLI::App app{
        "How the per-query error estimate relates to the true error, at poses along a scene's trajectory and several "
        "m'",
        "bench_error_estimate"};
    bench::add_common_options(app, quick, device_spec, out_dir, "4 poses, m' = 8,192 only");
    app.add_option("--scene", scene_path, "scene");
    app.add_option("--poses", pose_count, "poses along the trajectory")->check(CLI::Range(2, 10000));
    bench::parse(app, argc, argv);
    if (quick) pose_count = 4;
    const Scene scene = load_scene(scene_path);
    const Device device = select_device(device_spec_from(device_spec));
    const FftLibrary fft;
    const ComputeContext ctx = make_compute_context(device);
    const AssemblyPair pair = build_assembly_pair(scene, ctx, fft);
    const QueryVariant variant = query_variant_for(scene, Interpolation::tricubic);
    const std::vector<Pose> poses = accuracy_poses(scene, std::size_t(pose_count));

    const std::vector<QueryResult> reference =
        bench::exact_references(ctx, pair.spectra, variant, poses, [&](std::size_t i, const QueryResult&, double) {
          std::cerr << "\rreference " << i + 1 << "/" << poses.size() << std::flush;
        });
    std::cerr << "\n";

    auto engine = make_query_engine(ctx, pair.spectra, variant);
    const char* names[3] = {"energy", "force", "torque"};
    nlohmann::json rows = nlohmann::json::array();
    std::cout << "scene " << scene_path << ", " << variant_name(variant) << ", " << poses.size() << " poses, device "
              << describe_device(device.info) << "\n";
    const std::vector<std::size_t> ladder =
        quick ? std::vector<std::size_t>{8192} : std::vector<std::size_t>{8192, 16384, 32768};
    std::filesystem::create_directories(out_dir);
    // Per pose and m': the true error (reference - result) and the two band sums, as
    // differences of queries at m'/4, m'/2 and m' (equal to the kernels' band sums), for
    // trying other estimators from the same data (perf/error_estimate_spread.py).
    std::ofstream per_pose(std::filesystem::path(out_dir) / "poses.csv");
    per_pose << "modes,pose";
    for (const char* block : {"error", "band_a", "band_b"})
      for (const char* c : {"E", "Fx", "Fy", "Fz", "Tx", "Ty", "Tz"}) per_pose << "," << block << "_" << c;
    per_pose << "\n";
    const auto put = [&per_pose](const QueryResult& a, const QueryResult& b) {
      per_pose << "," << a.energy - b.energy;
      for (int c = 0; c < 3; ++c) per_pose << "," << a.force[c] - b.force[c];
      for (int c = 0; c < 3; ++c) per_pose << "," << a.torque[c] - b.torque[c];
    };
    for (const std::size_t m : ladder) {
      std::vector<QueryResult> at_quarter, at_half;
      engine->set_modes(m / 4);
      for (const Pose& p : poses) at_quarter.push_back(engine->query(p));
      engine->set_modes(m / 2);
      for (const Pose& p : poses) at_half.push_back(engine->query(p));
      engine->set_modes(m);
      std::vector<double> ratio[3];
      std::size_t covered[3] = {0, 0, 0}, compared = 0;
      std::vector<double> over[3];
      for (std::size_t i = 0; i < poses.size(); ++i) {
        const QueryResult r = engine->query(poses[i]);
        const QueryResult& ref = reference[i];
        per_pose << m << "," << i;
        put(ref, r);
        put(at_half[i], at_quarter[i]);
        put(r, at_half[i]);
        per_pose << "\n";
        if (r.flags != query_ok || ref.flags != query_ok) continue;
        ++compared;
        const double truth[3] = {std::abs(r.energy - ref.energy), (r.force - ref.force).norm(),
                                 (r.torque - ref.torque).norm()};
        const double estimate[3] = {r.error_estimate.energy, r.error_estimate.force, r.error_estimate.torque};
        for (int q = 0; q < 3; ++q) {
          if (estimate[q] > 0) ratio[q].push_back(kErrorEstimateScale * truth[q] / estimate[q]);
          if (estimate[q] >= truth[q]) ++covered[q];
          if (truth[q] > 0) over[q].push_back(estimate[q] / truth[q]);
        }
      }
      for (int q = 0; q < 3; ++q) {
        if ((q == 1 && !variant.force) || (q == 2 && !variant.torque) || ratio[q].empty()) continue;
        const double p05 = quantile(ratio[q], 0.05), p50 = quantile(ratio[q], 0.5), p95 = quantile(ratio[q], 0.95);
        const double coverage = double(covered[q]) / double(compared), median_over = quantile(over[q], 0.5);
        std::printf(
            "  m' %6zu %-6s  error / band rss: p05 %.2f p50 %.2f p95 %.2f   at scale %.1f: covers %.0f%%, "
            "median estimate / error %.2f\n",
            m, names[q], p05, p50, p95, kErrorEstimateScale, 100 * coverage, median_over);
        rows.push_back({{"modes", m},
                        {"output", names[q]},
                        {"ratio_p05", p05},
                        {"ratio_p50", p50},
                        {"ratio_p95", p95},
                        {"scale", kErrorEstimateScale},
                        {"coverage", coverage},
                        {"overestimate_median", median_over}});
      }
    }
    std::ofstream(std::filesystem::path(out_dir) / "error_estimate.json")
        << nlohmann::json{{"command", bench::command_line(argc, argv)},
                          {"date", bench::now_iso()},
                          {"device", device.info.name},
                          {"scene", scene_path},
                          {"strategy", variant_name(variant)},
                          {"poses", poses.size()},
                          {"rows", rows}}
               .dump(1)
        << "\n";
    return 0;
  });
}
