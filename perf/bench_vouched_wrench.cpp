// The wrench the loop renders against the exact one: each scene's scripted insertion is
// replayed through the same code as `snapfit run` (scheduler/haptics/assembly_session.h, at the
// m' the loop renders on this machine: the tuned m' less the rigid contact's share), on
// simulated time so that every tick runs; at --frames frames evenly along it, the
// geometric wrench sent (the engine's times the gain, times the trust its error estimate
// gave: scheduler/haptics/wrench_trust.h) is compared with the exact one (every mode, the
// exact-rotation product made for the frame's own rotation, times the same gain), and
// so is the raw wrench the same query gives without the trust.
//
// A frame is `accurate` when force and torque are within the larger of the relative
// tolerance and the floor (20 %, 0.05 N, 1 mN m) of the exact ones; else `conservative`
// when neither pushes against the exact one nor is stronger than it (beyond the floor);
// else `wrong`. Goal: no wrong frame in what is rendered.
//
//   bench_vouched_wrench --help lists its options.
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/query/query_engine.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/assembly_session.h"
#include "scheduler/tuning/engine_tuning.h"
#include "scheduler/haptics/trajectory.h"
#include "scheduler/haptics/wrench_trust.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

enum class Verdict { accurate, conservative, wrong };

Verdict judge(const Eigen::Vector3d& rendered, const Eigen::Vector3d& exact, double relative, double floor) {
  if ((rendered - exact).norm() <= std::max(relative * exact.norm(), floor)) return Verdict::accurate;
  if (rendered.dot(exact) >= 0 && rendered.norm() <= exact.norm() + floor) return Verdict::conservative;
  return Verdict::wrong;
}

Verdict judge(const Wrench& rendered, const Wrench& exact, const WrenchTrust& t) {
  const Verdict f = judge(rendered.force, exact.force, t.relative, t.force_n);
  const Verdict r = judge(rendered.torque, exact.torque, t.relative, t.torque_nm);
  return std::max(f, r);  // the worse of the two
}

struct Counts {
  std::size_t accurate = 0, conservative = 0, wrong = 0;
  void add(Verdict v) { ++(v == Verdict::accurate ? accurate : v == Verdict::conservative ? conservative : wrong); }
  std::size_t total() const { return accurate + conservative + wrong; }
  nlohmann::json json() const {
    return {{"accurate", accurate}, {"conservative", conservative}, {"wrong", wrong}};
  }
};

std::string percent(std::size_t part, std::size_t total) {
  return bench::fixed(total ? 100.0 * part / total : 0.0, 1) + " %";
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_vouched_wrench", [&] {
    bool quick = false;
    std::string device_spec, out_dir = "results/bench_vouched_wrench";
    std::vector<std::string> scenes = {"scenes/default.json", "scenes/three_pegs.json", "scenes/peg_hole_step.json"};
    std::size_t frames = 200;
    CLI::App app{"The rendered geometric wrench against the exact one at frames along each scene's insertion",
                 "bench_vouched_wrench"};
    bench::add_quick_and_out(app, quick, out_dir, "20 frames of scenes/default.json");
    bench::add_device_option(app, device_spec,
                             "OpenCL device (as `snapfit --device`); default: the loop's device, as `snapfit run`");
    app.add_option("--scenes", scenes, "comma-separated scenes")->delimiter(',');
    app.add_option("--frames", frames, "frames compared per scene")->check(CLI::Range(1, 100000));
    bench::parse(app, argc, argv);
    if (quick) frames = 20, scenes = {"scenes/default.json"};
    const std::string load_start = bench::read_loadavg();
    const Device device = bench::loop_device(device_spec);
    const ComputeContext ctx = make_compute_context(device);
    const FftLibrary fft;
    const WrenchTrust tolerance;

    nlohmann::json rows = nlohmann::json::array();
    std::ostringstream table;
    table << "| scene | m' rendered | frames | rendered: accurate / conservative / wrong | withheld (trust 0) | "
             "scaled (0 < trust < 1) | raw: accurate / conservative / wrong |\n|---|---|---|---|---|---|---|\n";
    for (const std::string& path : scenes) {
      const Scene scene = load_scene(path);
      const AssemblyPair pair = build_assembly_pair(scene, ctx, fft);
      const QueryVariant variant = query_variant_for(scene, Interpolation::tricubic);
      auto engine = make_query_engine(ctx, pair.spectra, variant);
      const TuningKey key = tuning_key_for(device.info, variant, pair.spectra, scene.frame_budget_ms, 0.25,
                                           scene.loop_rate_hz);
      TuneOptions tune;
      tune.budget_ms = scene.frame_budget_ms;
      const EngineTuning tuned = tune_engine(*engine, key, sample_trajectory(scene.trajectory, 100.0), tune, false,
                                             [](const std::string& m) { std::cerr << m << "\n"; });
      SessionOptions session;
      session.simulated_time = true;
      const SessionResult run = run_scripted_assembly(scene, pair.parts.part1.mesh, pair.parts.part2.mesh,
                                                      pair.spectra.spacing, *engine, tuned.result, session);
      const std::vector<FrameRecord>& log = run.loop.log;
      if (log.empty()) throw Error(path + ": the replay logged no frame");
      std::vector<std::size_t> picked;
      for (std::size_t i = 0; i < frames; ++i) picked.push_back(i * (log.size() - 1) / std::max<std::size_t>(1, frames - 1));
      std::vector<Pose> poses;
      for (std::size_t i : picked) poses.push_back(log[i].part);
      std::cerr << path << ": exact references at " << poses.size() << " frames...\n";
      const std::vector<QueryResult> exact =
          bench::exact_references(ctx, pair.spectra, variant, poses, [](std::size_t, const QueryResult&, double) {});

      const double gain = run.geometry_gain, torque_gain = gain * run.coupling.metres_per_unit;
      Counts rendered, raw;
      std::size_t withheld = 0, scaled = 0;
      for (std::size_t k = 0; k < picked.size(); ++k) {
        const FrameRecord& f = log[picked[k]];
        if (f.flags != query_ok || exact[k].flags != query_ok) continue;
        const Wrench x{gain * exact[k].force, torque_gain * exact[k].torque};
        engine->set_modes(f.modes);
        const QueryResult q = engine->query(f.part);
        const Wrench unvouched{gain * q.force, torque_gain * q.torque};
        rendered.add(judge(f.geometric, x, tolerance));
        raw.add(judge(unvouched, x, tolerance));
        withheld += f.trust == 0;
        scaled += f.trust > 0 && f.trust < 1;
      }
      const std::size_t n = rendered.total();
      const std::size_t modes = log[picked.back()].modes;
      std::cout << path << ": m' " << modes << ", " << n << " frames; rendered accurate "
                << percent(rendered.accurate, n) << ", conservative " << percent(rendered.conservative, n)
                << ", wrong " << percent(rendered.wrong, n) << " (withheld " << withheld << ", scaled " << scaled
                << "); raw wrong " << percent(raw.wrong, n) << "\n";
      table << "| " << path << " | " << modes << " | " << n << " | " << percent(rendered.accurate, n) << " / "
            << percent(rendered.conservative, n) << " / " << percent(rendered.wrong, n) << " | "
            << percent(withheld, n) << " | " << percent(scaled, n) << " | " << percent(raw.accurate, n) << " / "
            << percent(raw.conservative, n) << " / " << percent(raw.wrong, n) << " |\n";
      rows.push_back({{"scene", path},
                      {"modes", modes},
                      {"start_modes", run.start_modes},
                      {"contact_ms", run.contact_ms},
                      {"frames", n},
                      {"rendered", rendered.json()},
                      {"raw", raw.json()},
                      {"withheld", withheld},
                      {"scaled", scaled},
                      {"assembled", run.assembled}});
    }
    std::cout << "\n" << table.str();
    fs::create_directories(out_dir);
    nlohmann::json summary = bench::run_record(argc, argv, describe_device(device.info), load_start);
    summary["tolerance"] = {{"relative", tolerance.relative},
                            {"force_n", tolerance.force_n},
                            {"torque_nm", tolerance.torque_nm}};
    summary["scenes"] = rows;
    bench::write_json(fs::path(out_dir) / "summary.json", summary);
    std::cout << "wrote " << (fs::path(out_dir) / "summary.json").string() << "\n";
    return 0;
  });
}
