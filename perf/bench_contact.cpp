// The rigid contact's time per frame (scheduler/haptics/rigid_contact.h), on one thread and split
// over several (scheduler/haptics/parallel_contact.h), on the shipped scenes. Poses: the gain's
// reference pose (the fit) and that pose moved half a fine distance spacing along +-x,
// +-y, +-z, as contact_cost_ms times them for the loop. Beside each thread count, the
// straightforward double-precision evaluation (perf/reference_contact.h) as a reference.
// The rows are timed in turn within each round, so their ratio is measured side by side
// on the same load. --contact-spacing overrides the scenes' haptics.contact_spacing (more
// sample points when smaller). Each row also gives each pose's p50 and p99 with its points
// in contact: near the fit most of the time goes to points that turn out not to touch.
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
#include "perf/reference_contact.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/parallel_contact.h"
#include "scheduler/haptics/rigid_contact.h"

using namespace snapfit;
namespace fs = std::filesystem;

int main(int argc, char** argv) {
  return bench::guarded_main("bench_contact", [&] {
    bool quick = false;
    std::string device, out_dir = "results/bench_contact";
    std::vector<std::string> scenes = {"scenes/default.json", "scenes/three_pegs.json"};
    std::vector<unsigned> thread_counts = {1, 2, 4};
    long rounds = 200;
    double contact_spacing = 0;
    bool reference = true;
    CLI::App app{"The rigid contact's time per evaluation near the fit, on 1 and more threads, per shipped scene.",
                 "bench_contact"};
    bench::add_common_options(app, quick, device, out_dir, "20 rounds on scenes/default.json");
    app.add_option("--scenes", scenes, "comma-separated scenes")->delimiter(',');
    app.add_option("--threads", thread_counts, "comma-separated thread counts")
        ->delimiter(',')
        ->check(CLI::Range(1, 64));
    app.add_option("--rounds", rounds, "timed rounds per scene and thread count")->check(CLI::Range(1, 100000));
    app.add_option("--contact-spacing", contact_spacing,
                   "sample spacing of the contact (scene units; 0: each scene's haptics.contact_spacing)")
        ->check(CLI::NonNegativeNumber);
    app.add_flag("--reference,!--no-reference", reference,
                 "also time the straightforward double-precision evaluation on each thread count");
    bench::parse(app, argc, argv);
    if (quick) rounds = 20, scenes = {"scenes/default.json"};
    const std::string load_start = bench::read_loadavg();
    nlohmann::json results = nlohmann::json::array();
    std::ostringstream table;
    table
        << "| scene | sample points | evaluation | threads | p50 (ms) | p99 (ms) | speed-up over the reference (p50 of "
           "round ratios) |\n"
           "|---|---|---|---|---|---|---|\n";
    for (const std::string& path : scenes) {
      Scene scene = load_scene(path);
      if (contact_spacing > 0) scene.haptics.contact_spacing = contact_spacing;
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
      struct Row {
        std::string evaluation;
        unsigned threads;
        std::function<ContactWrench(const Pose&)> evaluate;
        std::size_t reference;  // its reference row, or itself
      };
      std::vector<Row> rows;
      for (unsigned t : thread_counts) {
        rows.push_back({"library", t, contact_evaluator(model, t), rows.size()});
        if (!reference) continue;
        rows.back().reference = rows.size();
        rows.push_back({"reference", t, contact_evaluator(model, t, bench::reference_contact_share), rows.size()});
      }
      std::vector<std::vector<double>> ms(rows.size()), round_ms(rows.size());
      [[maybe_unused]] volatile double kept = 0;  // the result is used, so the call is timed
      for (long r = 0; r < rounds; ++r)
        for (std::size_t e = 0; e < rows.size(); ++e) {
          double total = 0;
          for (const Pose& pose : poses) {
            const auto start = std::chrono::steady_clock::now();
            kept = rows[e].evaluate(pose).energy_j;
            const double t = 1e3 * seconds_since(start);
            ms[e].push_back(t);
            total += t;
          }
          round_ms[e].push_back(total);
        }
      for (std::size_t e = 0; e < rows.size(); ++e) {
        const Row& row = rows[e];
        std::vector<double> ratio;
        for (long r = 0; r < rounds; ++r) ratio.push_back(round_ms[row.reference][r] / round_ms[e][r]);
        const double p50 = quantile(ms[e], 0.5), p99 = quantile(ms[e], 0.99), speedup = quantile(ratio, 0.5);
        std::cout << path << ": " << points << " points, " << row.evaluation << ", " << row.threads
                  << " thread(s): p50 " << bench::fixed(p50, 3) << " ms, p99 " << bench::fixed(p99, 3) << " ms";
        if (row.reference != e) std::cout << ", x" << bench::fixed(speedup, 2) << " against the reference";
        std::cout << "\n";
        table << "| " << path << " | " << points << " | " << row.evaluation << " | " << row.threads << " | "
              << bench::fixed(p50, 3) << " | " << bench::fixed(p99, 3) << " | "
              << (row.reference != e ? bench::fixed(speedup, 2) : std::string("-")) << " |\n";
        nlohmann::json per_pose = nlohmann::json::array();
        for (std::size_t q = 0; q < poses.size(); ++q) {
          std::vector<double> pose_ms;
          for (std::size_t i = q; i < ms[e].size(); i += poses.size()) pose_ms.push_back(ms[e][i]);
          const std::size_t touching = row.evaluate(poses[q]).points;
          const double pose_p50 = quantile(pose_ms, 0.5), pose_p99 = quantile(pose_ms, 0.99);
          std::cout << "  pose " << q << ": " << touching << " points in contact, p50 " << bench::fixed(pose_p50, 3)
                    << " ms, p99 " << bench::fixed(pose_p99, 3) << " ms\n";
          per_pose.push_back({{"points_in_contact", touching}, {"p50_ms", pose_p50}, {"p99_ms", pose_p99}});
        }
        nlohmann::json result = {{"scene", path},          {"points", points}, {"evaluation", row.evaluation},
                                 {"threads", row.threads}, {"p50_ms", p50},    {"p99_ms", p99},
                                 {"poses", per_pose}};
        if (contact_spacing > 0) result["contact_spacing"] = contact_spacing;
        if (row.reference != e) result["speedup_vs_reference"] = speedup;
        results.push_back(result);
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
