// What a frame's query costs while part 2 rests at its fit. A part that settles there
// approaches the fit exponentially, so its offsets from it shrink through float's smallest
// normal (1.2e-38) into subnormals, whose arithmetic takes a slow path on x86. Queries at
// the scene's fit moved by 10^-k (in translation and rotation), timed in the calling thread
// as it is and inside a SubnormalFlush as the haptic loop's thread runs them
// (core/subnormal_flush.h); rounds interleaved, the median of the rounds' medians.
//
//   ./build/perf/bench_resting_pose [--quick] [--scene S] [--modes M] [--queries N] [--rounds R]
#include <CLI/CLI.hpp>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "core/quantile.h"
#include "core/subnormal_flush.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "snapfit/assembly.h"
#include "snapfit/scene.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

// The fit moved by `offset` along every translation axis and about every rotation axis.
Pose resting_at(const Pose& fit, double offset) {
  Pose p = fit;
  p.translation += Eigen::Vector3d(offset, -0.5 * offset, 0.2 * offset);
  p.rotation = (fit.rotation * Eigen::Quaterniond(1, 0.7 * offset, -1.4 * offset, 0.004 * offset)).normalized();
  return p;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_resting_pose", [&] {
    bool quick = false;
    std::string out_dir = "results/bench_resting_pose", scene_path = "scenes/default.json", device_spec;
    std::size_t modes = 16384, queries = 200;
    int rounds = 5;
    CLI::App app{"Queries at poses that rest at the fit (offsets down to subnormal floats), with and without "
                 "the loop thread's subnormal flush",
                 "bench_resting_pose"};
    bench::add_quick_and_out(app, quick, out_dir, "1 round of 50 queries");
    bench::add_device_option(app, device_spec,
                             "OpenCL device (as `snapfit --device`); default: the loop's device, as `snapfit run`");
    app.add_option("--scene", scene_path, "scene; the fit is its trajectory's last keyframe (else part 2's pose)");
    app.add_option("--modes", modes, "m'")->check(CLI::PositiveNumber);
    app.add_option("--queries", queries, "timed queries per offset and round")->check(CLI::Range(10, 1000000));
    app.add_option("--rounds", rounds, "rounds, interleaved")->check(CLI::Range(1, 1000));
    bench::parse(app, argc, argv);
    if (quick) rounds = 1, queries = 50;
    const std::string load_start = bench::read_loadavg();

    const Scene scene = load_scene(scene_path);
    AssemblyOptions options;
    options.device = device_spec.empty() ? bench::loop_device("").info.name : device_spec;
    const Assembly assembly(scene, options);
    auto engine = assembly.make_query_engine();
    engine->set_modes(std::min(modes, engine->max_modes()));
    const Pose fit = scene.trajectory.keyframes.empty() ? scene.part2.pose : scene.trajectory.keyframes.back().pose;

    const std::vector<double> offsets = {0, 1e-12, 1e-21, 1e-30, 1e-35, 1e-40, 1e-44};
    std::vector<std::vector<double>> medians[2];  // [flushed][offset][round]
    for (auto& m : medians) m.assign(offsets.size(), {});
    for (int round = 0; round < rounds; ++round)
      for (std::size_t o = 0; o < offsets.size(); ++o)
        for (int flushed = 0; flushed < 2; ++flushed) {
          std::optional<SubnormalFlush> flush;
          if (flushed) flush.emplace();
          const Pose pose = resting_at(fit, offsets[o]);
          for (int i = 0; i < 20; ++i) (void)engine->query(pose);
          std::vector<double> ms;
          for (std::size_t i = 0; i < queries; ++i) {
            const auto t = std::chrono::steady_clock::now();
            (void)engine->query(pose);
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count());
          }
          medians[flushed][o].push_back(quantile(ms, 0.5));
        }

    std::ostringstream table;
    table << "| offset from the fit | query p50, thread as it is (ms) | query p50, subnormals flushed (ms) |\n"
          << "|---|---|---|\n";
    nlohmann::json rows = nlohmann::json::array();
    for (std::size_t o = 0; o < offsets.size(); ++o) {
      const double plain = quantile(medians[0][o], 0.5), flushed = quantile(medians[1][o], 0.5);
      table << "| " << (offsets[o] == 0 ? std::string("0") : bench::sci(offsets[o], 0)) << " | "
            << bench::fixed(plain, 3) << " | " << bench::fixed(flushed, 3) << " |\n";
      rows.push_back({{"offset", offsets[o]},
                      {"query_ms_p50", plain},
                      {"query_ms_p50_flushed", flushed},
                      {"round_medians_ms", medians[0][o]},
                      {"round_medians_ms_flushed", medians[1][o]}});
    }
    std::cout << "m' " << engine->modes() << " on " << options.device << ", " << rounds << " rounds of " << queries
              << " queries\n"
              << table.str();
    fs::create_directories(out_dir);
    const nlohmann::json summary = {{"benchmark", "bench_resting_pose"},
                                    {"command", bench::command_line(argc, argv)},
                                    {"date", bench::now_iso()},
                                    {"load_start", load_start},
                                    {"load_end", bench::read_loadavg()},
                                    {"scene", scene_path},
                                    {"device", options.device},
                                    {"modes", engine->modes()},
                                    {"rows", rows}};
    bench::write_json(fs::path(out_dir) / "summary.json", summary);
    std::ofstream(fs::path(out_dir) / "summary.md") << table.str();
    std::cout << "wrote " << (fs::path(out_dir) / "summary.json").string() << ", summary.md\n";
    return 0;
  });
}
