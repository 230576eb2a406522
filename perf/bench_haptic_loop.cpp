// The haptic loop benchmark: the auto-tuned m' held in the 1 kHz loop for a
// long run on this machine. The scene's scripted trajectory is played back and forth
// by a ScriptedDevice for --seconds (default 60) of real time through the same code as
// `snapfit run` (scheduler/haptics/assembly_session.h). Reported: measured rate, frame-time
// p50/p99/max and histogram, misses and miss rate (target <= 0.1 %), every m' change,
// and the tuned m' next to seed 000's 4096 on a Tesla K20c (published, not measured).
//
//   bench_haptic_loop --help lists its options.
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sys/resource.h>

#include "core/quantile.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "pipeline/assembly_pair.h"
#include "report/chart_spec.h"
#include "report/loop_json.h"
#include "scheduler/haptics/assembly_session.h"
#include "scheduler/tuning/engine_tuning.h"
#include "scheduler/haptics/trajectory.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

struct Options {
  std::string scene_path = "scenes/default.json", out_dir = "results/bench_haptic_loop", device_spec;
  double seconds = 60, margin = 0.25;
  bool retune = false, quick = false;
  LoopWait wait = LoopWait::spin;
};

Options parse_options(int argc, char** argv) {
  Options o;
  std::string wait_name = "spin";
  CLI::App app{
      "The auto-tuned m' held in the 1 kHz loop for a long run: the scene's trajectory played back and "
      "forth through the same code as `snapfit run`",
      "bench_haptic_loop"};
  bench::add_quick_and_out(app, o.quick, o.out_dir, "3 s of loop (CI proves it runs; no timing is checked)");
  bench::add_device_option(app, o.device_spec,
                           "OpenCL device (as `snapfit --device`); default: PoCL's single-threaded driver when there "
                           "is one, which `snapfit run` picks for the loop, else the default");
  app.add_option("--scene", o.scene_path, "scene");
  app.add_option("--seconds", o.seconds, "seconds of loop")->check(cli::positive_number());
  app.add_flag("--retune", o.retune, "tune m' again instead of reading the tuning file");
  app.add_option("--margin", o.margin,
                 "the tuner keeps the p99 at most (1 - margin) of the frame budget (its own tuning file per margin)");
  app.add_option("--wait", wait_name, "how the loop waits for its tick: spin or sleep (as `snapfit run`)");
  bench::parse(app, argc, argv);
  o.wait = parse_loop_wait(wait_name);
  if (o.quick) o.seconds = 3;
  if (!(o.margin >= 0 && o.margin < 1)) throw Error("--margin: must be in [0, 1)");
  return o;
}

long major_faults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<long>(u.ru_majflt);
}

// Every missed frame: its work (wake-up to wrench sent) against the tuner's p99 model
// at the m' it ran with. Work within 1.5x of the model is the tail of that m'; far
// beyond it (4x) is a stall of the machine that a smaller m' would not have avoided.
struct Misses {
  nlohmann::json frames = nlohmann::json::array();
  std::size_t tail = 0, slow = 0, stall = 0, late = 0;
};
Misses classify_misses(const LoopReport& loop, const CostModel& model, double frame_budget_ms) {
  Misses m;
  for (std::size_t i = 0; i < loop.log.size(); ++i) {
    const FrameRecord& f = loop.log[i];
    if (!f.missed) continue;
    const double wake = loop.wake_late_ms[i], work = f.frame_ms - wake;
    const double predicted = model.predict_ms(f.modes);
    const double ratio = work / predicted;
    if (work <= 0.6 * frame_budget_ms)
      ++m.late;
    else if (ratio <= 1.5)
      ++m.tail;
    else if (ratio <= 4)
      ++m.slow;
    else
      ++m.stall;
    m.frames.push_back({{"time_s", f.time_s},
                        {"frame_ms", f.frame_ms},
                        {"wake_late_ms", wake},
                        {"work_ms", work},
                        {"modes", f.modes},
                        {"model_p99_ms", predicted}});
  }
  return m;
}

void print_loop(const SessionResult& run, const EngineTuning& tuned, long faults, const std::string& load_start,
                const std::string& load_end) {
  const LoopReport& loop = run.loop;
  std::cout << "frames " << loop.frames << " in " << loop.elapsed_s << " s: " << loop.measured_rate_hz
            << " Hz; frame ms p50 " << quantile(loop.frame_ms, 0.5) << ", p99 " << quantile(loop.frame_ms, 0.99)
            << ", max " << quantile(loop.frame_ms, 1.0) << "; misses " << loop.misses << " (" << 100 * loop.miss_rate()
            << " %, target <= 0.1 %), of which " << loop.late_wakeup_misses << " from waking late and "
            << loop.stall_misses << " stalls (not acted on); skipped ticks " << loop.skipped_ticks << "\n"
            << "wake-up lateness ms p50 " << quantile(loop.wake_late_ms, 0.5) << ", p99 "
            << quantile(loop.wake_late_ms, 0.99) << ", max " << quantile(loop.wake_late_ms, 1.0) << "\n"
            << "m' tuned " << tuned.result.chosen_modes << ", final " << loop.final_modes << ", "
            << loop.mode_changes.size() << " changes; seed 000 (published, K20c, translation only): 4096\n"
            << "loop wait: " << loop_wait_name(run.wait) << "; thread priority: " << run.priority.describe()
            << "; major page faults during the loop: " << faults << "\n"
            << "load average: start " << load_start << ", end " << load_end << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_haptic_loop", [&] {
    const Options o = parse_options(argc, argv);
    const std::string load_start = bench::read_loadavg();

    const Scene scene = load_scene(o.scene_path);
    const Device device = bench::loop_device(o.device_spec);  // as `snapfit run` picks it; --device overrides
    std::cout << "device " << describe_device(device.info) << "\n";
    const FftLibrary fft;
    const ComputeContext ctx = make_compute_context(device);
    const AssemblyPair pair = build_assembly_pair(scene, ctx, fft);
    const QueryVariant variant = query_variant_for(scene, Interpolation::tricubic);
    auto engine = make_query_engine(ctx, pair.spectra, variant);
    const TuningKey key =
        tuning_key_for(device.info, variant, pair.spectra, scene.frame_budget_ms, o.margin, scene.loop_rate_hz);
    TuneOptions tune_options;
    tune_options.budget_ms = scene.frame_budget_ms;
    tune_options.margin = o.margin;
    const EngineTuning tuned = tune_engine(*engine, key, sample_trajectory(scene.trajectory, 100.0), tune_options,
                                           o.retune, [](const std::string& m) { std::cerr << m << "\n"; });
    std::cout << "tuned m' = " << tuned.result.chosen_modes << (tuned.from_file ? " (tuning file)" : " (measured)")
              << ", model p99 " << tuned.result.model.predict_ms(tuned.result.chosen_modes) << " ms\n"
              << "running the loop for " << o.seconds << " s at " << scene.loop_rate_hz << " Hz...\n";

    SessionOptions session;
    session.duration_s = o.seconds;
    session.loop_back = true;
    session.keep_log = true;  // the missed frames' details below
    session.wait = o.wait;
    const long faults_before = major_faults();
    const SessionResult run = run_scripted_assembly(scene, pair.parts.part1.mesh, pair.parts.part2.mesh,
                                                    pair.spectra.spacing, *engine, tuned.result, session);
    const long loop_major_faults = major_faults() - faults_before;
    const LoopReport& loop = run.loop;
    const std::string load_end = bench::read_loadavg();
    print_loop(run, tuned, loop_major_faults, load_start, load_end);
    const Misses missed = classify_misses(loop, tuned.result.model, scene.frame_budget_ms);
    std::cout << "missed frames by their work against the model p99 at their m': woke late " << missed.late
              << ", within 1.5x " << missed.tail << ", 1.5-4x " << missed.slow << ", beyond 4x (stalls) "
              << missed.stall << "\n";

    fs::create_directories(o.out_dir);
    nlohmann::json report = loop_json(loop);
    report.update(bench::run_record(argc, argv, device.info.name, load_start));
    report.update({{"driver", device.info.driver_version},
                   {"scene", o.scene_path},
                   {"variant", variant_name(variant)},
                   {"seconds", o.seconds},
                   {"tuned_modes", tuned.result.chosen_modes},
                   {"tuning_from_file", tuned.from_file},
                   {"final_modes", loop.final_modes},
                   {"mode_changes", mode_changes_json(loop.mode_changes)},
                   {"missed_frames", missed.frames},
                   {"major_page_faults", loop_major_faults},
                   {"missed_by_work",
                    {{"woke_late", missed.late},
                     {"within_1_5x_model", missed.tail},
                     {"1_5x_to_4x", missed.slow},
                     {"beyond_4x", missed.stall}}},
                   {"seed000_published_modes", 4096},
                   {"wait", loop_wait_name(run.wait)},
                   {"priority",
                    {{"threads_raised", run.priority.threads},
                     {"realtime", run.priority.realtime},
                     {"failed", run.priority.failed},
                     {"described", run.priority.describe()}}}});
    std::ofstream(fs::path(o.out_dir) / "haptic_loop.json") << report.dump(2) << "\n";
    Chart hist = histogram_chart("Haptic loop frame time, " + std::to_string(loop.frames) +
                                     " frames, m' = " + std::to_string(tuned.result.chosen_modes),
                                 "frame time (ms)", loop.frame_ms, 80, true);
    const std::string page =
        bench::write_charts(o.out_dir, "bench_haptic_loop: frame times", bench::command_line(argc, argv), {hist});
    std::cout << "wrote " << o.out_dir << "/haptic_loop.json and " << page << "\n";
    return 0;
  });
}
