// What a frame pays when the loop's m' governor steps up on the exact-rotation product
// made in the background: set_modes remakes the product for the larger m' in the frame
// (and waits for the worker's product in flight), request_modes leaves it to the worker
// and keeps the smaller m' until the product is there. Side by side in one run: a pose
// turning slowly at the loop's rate, m' stepped up and down between two levels, each step
// up made the one way or the other in turn; the frame with the step and the largest of
// the next 50 frames are timed.
//
//   ./build/perf/bench_mode_step [--quick] [--scene S] [--steps N] [--low M] [--high M]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "core/quantile.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "snapfit/assembly.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

constexpr int kAfter = 50;     // frames timed after a step
constexpr int kBetween = 200;  // frames between steps

double ms_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_mode_step", [&] {
    bool quick = false;
    std::string out_dir = "results/bench_mode_step", scene_path = "scenes/default.json", device_spec;
    int steps = 40;
    std::size_t low = 16384, high = 32768;
    CLI::App app{"The frame that steps m' up on the background exact product: set_modes against request_modes",
                 "bench_mode_step"};
    bench::add_quick_and_out(app, quick, out_dir, "6 steps");
    bench::add_device_option(app, device_spec,
                             "OpenCL device (as `snapfit --device`); default: the loop's device, as `snapfit run`");
    app.add_option("--scene", scene_path, "scene");
    app.add_option("--steps", steps, "steps up, half made each way")->check(CLI::Range(2, 100000));
    app.add_option("--low", low, "the smaller m'")->check(CLI::PositiveNumber);
    app.add_option("--high", high, "the larger m'")->check(CLI::PositiveNumber);
    bench::parse(app, argc, argv);
    if (quick) steps = 6;
    if (high <= low) throw Error("--high must be larger than --low");
    const std::string load_start = bench::read_loadavg();

    const Scene scene = load_scene(scene_path);
    AssemblyOptions options;
    options.device = device_spec.empty() ? bench::loop_device("").info.name : device_spec;
    const Assembly assembly(scene, options);
    const QueryVariant variant =
        with_strategy(assembly.query_variant(), QueryStrategy::exact_product, ProductUpdate::background);
    auto engine = assembly.make_query_engine(variant);
    engine->set_modes(low);

    // A slow turn about the part's start pose, one pose per 1 ms tick.
    Pose pose = scene.part2.pose;
    const Eigen::Quaterniond start = pose.rotation;
    long tick = 0;
    const auto frame = [&] {
      const double angle = 0.2 * std::sin(1e-3 * double(tick++));  // rad
      pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitX())) * start;
      const auto t = std::chrono::steady_clock::now();
      (void)engine->query(pose);
      return t;
    };
    const auto run_frames = [&](int n, double* largest) {
      for (int i = 0; i < n; ++i) {
        const auto next = std::chrono::steady_clock::now() + std::chrono::milliseconds(1);
        const auto t = frame();
        if (largest) *largest = std::max(*largest, ms_since(t));
        std::this_thread::sleep_until(next);
      }
    };
    run_frames(kBetween, nullptr);

    std::vector<double> step_ms[2], after_ms[2];
    std::vector<double> reached_frames[2];  // frames until the engine reports the larger m'
    for (int s = 0; s < steps; ++s) {
      const int way = s % 2;  // 0: set_modes, 1: request_modes
      const auto t = std::chrono::steady_clock::now();
      if (way == 0)
        engine->set_modes(high);
      else
        engine->request_modes(high);
      (void)engine->query(pose);
      step_ms[way].push_back(ms_since(t));
      double largest = 0;
      int reached = engine->modes() == high ? 0 : -1;
      for (int i = 0; i < kAfter; ++i) {
        run_frames(1, &largest);
        if (reached < 0 && engine->modes() == high) reached = i + 1;
      }
      after_ms[way].push_back(largest);
      reached_frames[way].push_back(reached < 0 ? kAfter + 1 : reached);
      engine->set_modes(low);  // a step down never waits (both ways)
      run_frames(kBetween, nullptr);
    }

    const char* names[2] = {"set_modes", "request_modes"};
    std::ostringstream table;
    table << "| m' step " << low << " -> " << high << " by | steps | step frame p50 / max (ms) | "
          << "largest of the next " << kAfter << " frames, p50 / max (ms) | frames until the larger m', p50 / max |\n"
          << "|---|---|---|---|---|\n";
    nlohmann::json rows = nlohmann::json::array();
    for (int w = 0; w < 2; ++w) {
      const auto stat = [](const std::vector<double>& v) {
        return std::make_pair(quantile(v, 0.5), *std::max_element(v.begin(), v.end()));
      };
      const auto [sp50, smax] = stat(step_ms[w]);
      const auto [ap50, amax] = stat(after_ms[w]);
      const auto [rp50, rmax] = stat(reached_frames[w]);
      table << "| " << names[w] << " | " << step_ms[w].size() << " | " << bench::fixed(sp50, 3) << " / "
            << bench::fixed(smax, 3) << " | " << bench::fixed(ap50, 3) << " / " << bench::fixed(amax, 3) << " | "
            << rp50 << " / " << rmax << " |\n";
      rows.push_back({{"by", names[w]},
                      {"steps", step_ms[w].size()},
                      {"step_frame_ms", step_ms[w]},
                      {"largest_after_ms", after_ms[w]},
                      {"frames_until_larger_modes", reached_frames[w]}});
    }
    std::cout << table.str();
    fs::create_directories(out_dir);
    const nlohmann::json summary = {{"benchmark", "bench_mode_step"},
                                    {"command", bench::command_line(argc, argv)},
                                    {"date", bench::now_iso()},
                                    {"load_start", load_start},
                                    {"load_end", bench::read_loadavg()},
                                    {"scene", scene_path},
                                    {"modes", {low, high}},
                                    {"rows", rows}};
    bench::write_json(fs::path(out_dir) / "summary.json", summary);
    std::ofstream(fs::path(out_dir) / "summary.md") << table.str();
    std::cout << "wrote " << (fs::path(out_dir) / "summary.json").string() << ", summary.md\n";
    return 0;
  });
}
