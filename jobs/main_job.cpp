// snapfit/job.h: the main job on an OpenCL device (Behandish & Ilies 2016 sections 3-4):
// the parts, the device and its self-check, the fields, the spectra, the strategy and m',
// and the scripted session; a VPS scene goes to jobs/vps_job.cpp after the parts.
#include <algorithm>
#include <chrono>
#include <sstream>

#include "core/progress.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device_check.h"
#include "jobs/job_steps.h"
#include "jobs/job_text.h"
#include "pipeline/assembly_pair.h"
#include "pipeline/scene_summary.h"
#include "scheduler/haptics/contact_reserve.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/tuning/accuracy.h"
#include "scheduler/tuning/loop_devices.h"
#include "snapfit/job_facts.h"
#include "snapfit/tuning.h"
#include "snapfit/error.h"
#include "snapfit/job.h"

namespace snapfit {
namespace {

// The variant the request's strategy names for `scene` (auto: the scene's tricubic
// variant, the starting point of the measured choice).
QueryVariant named_strategy(const Scene& scene, const std::string& name) {
  const std::optional<QueryStrategy> strategy = strategy_named(name);
  if (name != "auto" && !strategy) {
    std::string known = "auto";
    for (QueryStrategy s : query_strategies()) known += std::string(", ") + strategy_name(s);
    throw Error("strategy '" + name + "': expected one of " + known);
  }
  QueryVariant v = query_variant_for(scene, Interpolation::tricubic);
  if (v.translation_only) {
    if (strategy && strategy != QueryStrategy::tricubic)
      throw Error("strategy '" + name + "': a translation-only scene has one strategy, the translation lines");
    return v;
  }
  for (int part : {1, 2})
    if (strategy == QueryStrategy::near_far &&
        (part == 1 ? scene.part1 : scene.part2).descriptor.source == SpectrumSource::spheres)
      throw Error("strategy 'near-far': its near part sums the parts' grid samples, and part " + std::to_string(part) +
                  "'s descriptor.source is \"spheres\" (use \"grid\" or another strategy)");
  return strategy ? with_strategy(v, *strategy, ProductUpdate::background) : v;
}

// "[3/7]": the device, opened and self-checked.
ComputeContext open_checked_device(const JobRequest& request, const JobOutput& out, JobRecord& record) {
  out.say("[3/7] opening the OpenCL device and checking it\n");
  const Device device = select_device(device_spec_from(request.device));
  out.say("    device " + describe_device(device.info) + "\n");
  ComputeContext ctx = make_compute_context(device);
  const DeviceCheckResult check = run_device_check(ctx, false);
  std::ostringstream line;
  line << "    self-check " << (check.passed ? "passed" : "FAILED") << " (relative error " << check.relative_error
       << ", program " << (check.origin == ProgramOrigin::cache_hit ? "from cache" : "compiled") << " in "
       << check.build_ms << " ms)\n";
  out.say(line.str());
  if (!check.passed)
    throw Error("device " + device.info.name + " failed its self-check; choose another (JobRequest::device)");
  record.device = device.info;
  record.check = check;
  return ctx;
}

// "[4/7]" and "[5/7]": both parts' fields, then the spectra.
void compute_fields_and_spectra(AssemblyPair& pair, const ComputeContext& ctx, const JobRequest& request,
                                const JobOutput& out) {
  const Scene& scene = pair.scene;
  std::ostringstream head;
  head << "[4/7] descriptor fields of both parts at spacing " << pair.grids.spacing << " " << scene.units
       << " (from the field cache when present)\n";
  out.say(head.str());
  PairOptions options;
  if (request.progress) options.descriptors.progress = pass_progress_bars();
  options.note = out.note;
  // The near-far strategy's near field, only where it may run: named, or a candidate of
  // the measured choice (scheduler/tuning/accuracy.h); a fixed m' with "auto" runs tricubic.
  options.near_field = request.strategy == "near-far" || (request.strategy == "auto" && !request.modes);
  for (int part = 1; part <= 2; ++part) {
    const GridSpec& grid = pair.grid(part);
    std::ostringstream line;
    line << "  part " << part << ": grid " << grid.dims.x() << " x " << grid.dims.y() << " x " << grid.dims.z() << " = "
         << grid.count() << " points, " << pair.part(part).mesh.triangles.size() << " triangles\n";
    out.say(line.str());
    compute_assembly_fields(pair, ctx, options, part);
    std::ostringstream summary;
    print_fields_summary(summary, pair.fields(part));
    out.say(summary.str());
  }
  out.say("[5/7] spectra (from the spectra cache when present) and the query engine\n");
  const FftLibrary fft;
  compute_assembly_spectra(pair, ctx, fft, options);
}

// "[6/7]" with a fixed m': the named strategy's engine, not tuned.
std::unique_ptr<QueryEngine> fixed_modes_engine(const ComputeContext& ctx, const AssemblyPair& pair,
                                                const QueryVariant& variant, const JobRequest& request,
                                                const JobOutput& out, JobRecord& record) {
  auto engine = make_query_engine(ctx, pair.spectra, variant);
  record.tuning = pick_modes({TimingPoint{std::min(request.modes, engine->max_modes()), 0, 0, 0, 0}},
                             pair.scene.frame_budget_ms, request.margin);
  record.loop_device = ctx.device.info;
  record.strategy = variant_name(variant);
  record.strategy_label = strategy_short_name(variant);
  record.strategy_chosen_by = request.strategy == "auto" ? "JobRequest::modes (not measured)" : "JobRequest::strategy";
  out.say("    " + record.strategy + ", m' = " + std::to_string(record.tuning.chosen_modes) +
          " (JobRequest::modes; not tuned)\n");
  return engine;
}

// The rigid contact the loop will add, and its time per frame, reserved from the frame
// before the strategy and m' are chosen: the strategy table then reports the errors of
// the m' the loop renders beside the contact.
void reserve_contact_time(const AssemblyPair& pair, const JobRequest& request, const JobOutput& out,
                          JobRecord& record) {
  const Scene& scene = pair.scene;
  record.contact =
      rigid_contact_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.spectra.spacing, &record.contact_off);
  if (!record.contact || request.modes) return;
  const ContactReserve reserve = contact_reserve(scene, pair.part(1).mesh, pair.part(2).mesh, record.contact,
                                                 record.device, request.retune, out.note);
  record.contact_reserved_ms = reserve.reserved_ms;
  std::ostringstream line;
  line << "    rigid contact: " << reserve.measured_ms << " ms a frame (p99 near the fit"
       << (reserve.from_file ? ", from " + reserve.file : std::string(", measured")) << "); "
       << record.contact_reserved_ms << " ms of the " << scene.frame_budget_ms
       << " ms frame reserved for it before m' is chosen\n";
  out.say(line.str());
}

// What the strategies' errors are measured with: the scene's budget less the contact's share.
AccuracyOptions strategy_accuracy_options(const Scene& scene, const JobRequest& request, const JobOutput& out,
                                          const JobRecord& record) {
  AccuracyOptions accuracy;
  accuracy.budget_ms = scene.frame_budget_ms;
  accuracy.margin = request.margin;
  accuracy.reserved_ms = record.contact_reserved_ms;
  accuracy.retune = request.retune;
  accuracy.note = out.note;
  if (request.progress) accuracy.progress = pass_progress_bars();
  return accuracy;
}

// "[6/7]" tuned: m' on this device (and the others with no device named), then with
// strategy "auto" the most accurate strategy that fits, from the strategy file. Not
// measured yet, the loop starts on the tuned variant (tricubic): whatever it renders, its
// error estimate vouches for (scheduler/haptics/wrench_trust.h), and the strategies are measured
// after the loop (measure_strategies_after_loop) rather than before its first frame.
LoopDevices tuned_loop_devices(const ComputeContext& ctx, const AssemblyPair& pair, const QueryVariant& variant,
                               const JobRequest& request, const JobOutput& out, JobRecord& record) {
  const Scene& scene = pair.scene;
  LoopDeviceOptions tune;
  tune.margin = request.margin;
  tune.retune = request.retune;
  tune.other_devices = device_spec_from(request.device).empty();
  tune.note = out.note;
  if (request.progress) {
    const auto bars = pass_progress_bars();  // one bar per sweep, finished when it ends
    tune.tune.progress = [bars](std::uint64_t done, std::uint64_t total) { bars("    tuning m'", done, total); };
  }
  tune.on_start = [&](const DeviceInfo& info) {
    if (info.index != ctx.device.info.index) out.say("    also tuning " + describe_device(info) + "\n");
  };
  tune.on_tuned = [&](const TunedDevice& d) {
    const std::string where = d.tuning.from_file ? "from the tuning file " + d.tuning.path
                              : d.tuning.saved   ? "measured and saved to " + d.tuning.path
                                                 : std::string("measured, not saved: no m' fits the budget");
    out.say("    " + where + "\n" + tuning_table(d.tuning.result));
  };
  LoopDevices devices = tune_loop_devices(ctx, scene, pair.spectra, variant, tune);
  record.strategy_chosen_by = "JobRequest::strategy";
  if (request.strategy == "auto") {
    const AccuracyOptions accuracy = strategy_accuracy_options(scene, request, out, record);
    if (const std::optional<StrategyChoice> choice =
            stored_query_strategy(devices.loop().ctx, scene, pair.spectra, accuracy)) {
      out.say(strategies_text(*choice));
      record.strategies = choice->report;
      record.strategy_file = choice->path;
      record.strategy_chosen_by = "lowest error that fits (strategy file)";
      if (variant_name(choice->chosen().variant) != variant_name(variant))
        use_variant_on_loop_device(devices, scene, pair.spectra, choice->chosen().variant, tune);
    } else {
      record.strategy_chosen_by = "safe start (the strategies are measured after the loop)";
      out.say("    the strategies' errors are not measured yet on this device: the loop starts on " +
              variant_name(variant) +
              ", whose error estimate vouches for what it renders, and they are measured after it\n");
    }
  }
  const TunedDevice& chosen = devices.loop();
  record.strategy = variant_name(chosen.engine->variant());
  record.strategy_label = strategy_short_name(chosen.engine->variant());
  if (devices.devices.size() > 1)
    out.say("    the loop runs on " + chosen.ctx.device.info.name + " (of " + std::to_string(devices.devices.size()) +
            " tuned devices: " +
            (chosen.ctx.device.info.runs_in_caller_thread() ? "runs kernels in the loop's own thread, " : "") + "m' " +
            std::to_string(chosen.tuning.result.chosen_modes) + ", scheduler/tuning/device_choice.h)\n");
  record.tuning = chosen.tuning.result;
  record.tuning_key = chosen.key.text();
  record.loop_device = chosen.ctx.device.info;
  return devices;
}

// The strategies the loop did not wait for: measured and saved after it, so that the
// next run renders the most accurate one that fits; the record says what this run rendered.
void measure_strategies_after_loop(const AssemblyPair& pair, const LoopDevices& devices, const JobRequest& request,
                                   const JobOutput& out, JobRecord& record) {
  out.say("    measuring the strategies' errors for the next run (the loop did not wait for them)\n");
  const AccuracyOptions accuracy = strategy_accuracy_options(pair.scene, request, out, record);
  const StrategyChoice choice = choose_query_strategy(devices.loop().ctx, pair.scene, pair.spectra, accuracy);
  out.say(strategies_text(choice));
  record.strategies = choice.report;
  record.strategies->why =
      "a safe start; the next run renders " + variant_name(choice.chosen().variant) + ": " + choice.report.why;
  record.strategy_file = choice.path;
}

}  // namespace

PreparedJob prepare_job(const Scene& scene, const JobRequest& request, const JobOutput& out,
                        std::shared_ptr<AssemblyPair> pair) {
  const QueryVariant variant = named_strategy(scene, request.strategy);  // a bad name fails before the work
  PreparedJob job;
  job.pair = std::move(pair);
  job.record = std::make_shared<JobRecord>();
  job.record->pair = job.pair;
  job.ctx = std::make_unique<ComputeContext>(open_checked_device(request, out, *job.record));
  compute_fields_and_spectra(*job.pair, *job.ctx, request, out);
  const auto& dims = job.pair->spectra.dims;
  std::ostringstream fft;
  fft << "    FFT grid " << dims[0] << " x " << dims[1] << " x " << dims[2]
      << (job.pair->spectra_from_cache ? " (cached)" : "") << ", query variant tuned first: " << variant_name(variant)
      << "\n";
  out.say(fft.str());

  std::ostringstream step6;
  step6 << "[6/7] the query strategy and m' for a " << scene.frame_budget_ms << " ms frame on this device\n";
  out.say(step6.str());
  reserve_contact_time(*job.pair, request, out, *job.record);
  if (request.modes) {
    job.fixed_engine = fixed_modes_engine(*job.ctx, *job.pair, variant, request, out, *job.record);
    job.loop_engine = job.fixed_engine.get();
  } else {
    job.devices =
        std::make_unique<LoopDevices>(tuned_loop_devices(*job.ctx, *job.pair, variant, request, out, *job.record));
    job.loop_engine = job.devices->loop().engine.get();
  }
  return job;
}

std::shared_ptr<AssemblyPair> prepare_job_parts(const Scene& scene, const JobRequest& request, const JobOutput& out) {
  if (!(request.margin >= 0 && request.margin < 1)) throw Error("margin: must be in [0, 1)");
  named_strategy(scene, request.strategy);  // a bad name fails before the work
  out.say("[2/7] building and validating both parts (in parallel)\n");
  auto pair = std::make_shared<AssemblyPair>(prepare_assembly_pair(scene));
  std::ostringstream summary;
  print_scene_summary(summary, scene, pair->parts, pair->plan);
  out.say(summary.str());
  return pair;
}

JobResult run_job(const Scene& scene, const JobRequest& request) {
  const auto started = std::chrono::steady_clock::now();
  const JobOutput out = job_output(request);
  std::shared_ptr<AssemblyPair> pair = prepare_job_parts(scene, request, out);
  if (uses_vps(scene.method)) return run_vps_job(pair, request, out);
  PreparedJob job = prepare_job(scene, request, out, pair);
  run_session_step(scene, request, out, "m' = " + std::to_string(job.record->tuning.chosen_modes), *job.record,
                   [&](const SessionOptions& session) {
                     SessionOptions with_contact = session;
                     if (job.record->contact_reserved_ms > 0) with_contact.contact_ms = job.record->contact_reserved_ms;
                     const double before =
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
                     SessionResult result =
                         run_scripted_assembly(scene, pair->part(1).mesh, pair->part(2).mesh, pair->spectra.spacing,
                                               *job.loop_engine, job.record->tuning, with_contact);
                     job.record->seconds_to_first_frame = before + result.setup_s;
                     return result;
                   });
  if (request.strategy == "auto" && !request.modes && !job.record->strategies)
    measure_strategies_after_loop(*job.pair, *job.devices, request, out, *job.record);
  if (job.record->seconds_to_first_frame > 0) {
    std::ostringstream ready;
    ready << "    ready to touch: the loop's first frame came " << job.record->seconds_to_first_frame
          << " s after the job started\n";
    out.say(ready.str());
  }
  return job_result(std::move(*job.record));
}

}  // namespace snapfit
