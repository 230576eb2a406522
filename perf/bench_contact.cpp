// The rigid contact's time per frame (scheduler/rigid_contact.h), on one thread and split
// over several (scheduler/parallel_contact.h), on the shipped scenes. Poses: the gain's
// reference pose (the fit) and that pose moved half a fine distance spacing along +-x,
// +-y, +-z, as contact_cost_ms times them for the loop. The thread counts are timed in
// turn within each round, so their ratio is measured side by side on the same load.
//
//   bench_contact --help lists its options.
#include <chrono>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "core/quantile.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptic_setup.h"
#include "scheduler/parallel_contact.h"
#include "scheduler/rigid_contact.h"

using namespace snapfit;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return bench::guarded_main("bench_contact", [&] {
    bool quick = false;
    std::string device, out_dir = "results/bench_contact";
    std::vector<std::string> scenes = {"scenes/default.json", "scenes/three_pegs.json"};
    std::vector<unsigned> thread_counts = {1, 2, 4};
    long rounds = 200;
    CLI::App app{"The rigid contact's time per evaluation near the fit, on 1 and more threads, per shipped scene.",
                 "bench_contact"};
    bench::add_common_options(app, quick, device, out_dir, "20 rounds on scenes/default.json");
    app.add_option("--scenes", scenes, "comma-separated scenes")->delimiter(',');
    app.add_option("--threads", thread_counts, "comma-separated thread counts")
        ->delimiter(',')
        ->check(CLI::Range(1, 64));
    app.add_option("--rounds", rounds, "timed rounds per scene and thread count")->check(CLI::Range(1, 100000));
    bench::parse(app, argc, argv);
    if (quick) rounds = 20, scenes = {"scenes/default.json"};
    const std::string load_start = bench::read_loadavg();
    nlohmann::json results = nlohmann::json::array();
    std::ostringstream table;
    table << "| scene | sample points | threads | p50 (ms) | p99 (ms) | speed-up (p50 of round ratios) |\n"
             "|---|---|---|---|---|---|\n";
    for (const std::string& path : scenes) {
      const Scene scene = load_scene(path);
      const AssemblyPair pair = prepare_assembly_pair(scene);
      std::string why_off;
      const auto model = rigid_contact_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing, &why_off);
      if (!model) {
        std::cout << path << ": no rigid contact (" << (why_off.empty() ? "off in the scene" : why_off) << ")\n";
        continue;
      }
      const std::size_t points = model->part1_samples.points.size() + model->part2_samples.points.size();
      std::vector<Pose> poses = gain_probe_poses(scene, 0.5 * model->part1_distance.fine_spacing());
      poses.push_back(gain_reference_pose(scene));
      std::vector<std::function<ContactWrench(const Pose&)>> evaluators;
      for (unsigned t : thread_counts) evaluators.push_back(contact_evaluator(model, t));
      std::vector<std::vector<double>> ms(thread_counts.size()), round_ms(thread_counts.size());
      [[maybe_unused]] volatile double kept = 0;  // the result is used, so the call is timed
      for (long r = 0; r < rounds; ++r)
        for (std::size_t e = 0; e < evaluators.size(); ++e) {
          double total = 0;
          for (const Pose& pose : poses) {
            const auto start = std::chrono::steady_clock::now();
            kept = evaluators[e](pose).energy_j;
            const double t = 1e3 * bench::seconds_since(start);
            ms[e].push_back(t);
            total += t;
          }
          round_ms[e].push_back(total);
        }
      for (std::size_t e = 0; e < evaluators.size(); ++e) {
        std::vector<double> ratio;
        for (long r = 0; r < rounds; ++r) ratio.push_back(round_ms[0][r] / round_ms[e][r]);
        const double p50 = quantile(ms[e], 0.5), p99 = quantile(ms[e], 0.99), speedup = quantile(ratio, 0.5);
        std::cout << path << ": " << points << " points, " << thread_counts[e] << " thread(s): p50 "
                  << bench::fixed(p50, 3) << " ms, p99 " << bench::fixed(p99, 3) << " ms, x" << bench::fixed(speedup, 2)
                  << " against " << thread_counts[0] << "\n";
        table << "| " << path << " | " << points << " | " << thread_counts[e] << " | " << bench::fixed(p50, 3) << " | "
              << bench::fixed(p99, 3) << " | " << bench::fixed(speedup, 2) << " |\n";
        results.push_back({{"scene", path},
                           {"points", points},
                           {"threads", thread_counts[e]},
                           {"p50_ms", p50},
                           {"p99_ms", p99},
                           {"speedup_vs_first", speedup}});
      }
    }
    fs::create_directories(out_dir);
    nlohmann::json record = bench::run_record(argc, argv, device, load_start);
    record["rounds"] = rounds;
    record["hardware_threads"] = std::thread::hardware_concurrency();
    record["results"] = results;
    std::ofstream(fs::path(out_dir) / "summary.json") << record.dump(2) << "\n";
    std::ofstream(fs::path(out_dir) / "summary.md") << table.str();
    std::cout << "\n" << table.str() << "\nwrote " << (fs::path(out_dir) / "summary.json").string() << ", summary.md\n";
    return 0;
  });
}
