#include "scheduler/tuning/engine_tuning.h"

#include <chrono>
#include <sstream>

#include "core/hash.h"
#include "engine/runtime/kernel_sources.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/trajectory.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/haptic_loop.h"

namespace snapfit {

TuningKey tuning_key_for(const DeviceInfo& device, const QueryVariant& variant, const PairSpectra& spectra,
                         double budget_ms, double margin, double pace_hz) {
  TuningKey key;
  key.platform = device.platform_name + " " + device.platform_version;
  key.device = device.name;
  key.driver = device.driver_version;
  key.variant = variant_name(variant);
  std::ostringstream features;
  // The query kernels' source: timings taken with other kernels say nothing about these.
  const std::string kernels =
      kernel_source("spectrum_sample") + kernel_source("pose_query") +
      (variant.rotation == RotationMethod::exact_product ? kernel_source("rotated_product") : "");
  features << "fft " << spectra.dims[0] << "x" << spectra.dims[1] << "x" << spectra.dims[2] << " exact_rotation "
           << spectra.part2.deconvolved_width << " spacing " << spectra.spacing << " kernels "
           << hex64(fnv1a64(kernels));
  // The exact product's ladder ends at its max_modes().
  if (variant.rotation == RotationMethod::exact_product)
    features << " product_modes " << (variant.product_modes ? std::to_string(variant.product_modes) : "every");
  key.scene_features = features.str();
  key.budget_ms = budget_ms;
  key.margin = margin;
  key.pace_hz = pace_hz;
  return key;
}

std::vector<Pose> tuning_poses(const Scene& scene) {
  if (scene.trajectory.keyframes.empty()) return {scene.part2.pose};
  return sample_trajectory(scene.trajectory, 100.0);
}

QueryTimer engine_query_timer(QueryEngine& engine, std::vector<Pose> poses, double pace_hz) {
  if (poses.empty()) throw Error("auto-tuning: no poses to time queries at");
  return [&engine, poses = std::move(poses), pace_hz, next = std::size_t(0)](std::size_t modes,
                                                                             std::size_t count) mutable {
    engine.set_modes(modes);
    std::vector<double> times;
    times.reserve(count);
    const LoopClock clock = steady_loop_clock();
    for (std::size_t i = 0; i < count; ++i) {
      if (pace_hz > 0) clock.wait_until((i + 1) / pace_hz);
      const auto t0 = std::chrono::steady_clock::now();
      engine.query(poses[next++ % poses.size()]);
      times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    return times;
  };
}

EngineTuning tune_and_keep(const TuningKey& key, const QueryTimer& timer, std::size_t max_modes, TuneOptions options,
                           bool retune, const std::function<void(const std::string&)>& note) {
  EngineTuning out;
  out.path = tuning_file_path(key);
  if (!retune)
    if (std::optional<TuningResult> cached = load_tuning(key, note)) {
      out.result = *cached;
      out.from_file = true;
      return out;
    }
  options.budget_ms = key.budget_ms;
  options.margin = key.margin;
  out.result = tune_modes(timer, max_modes, options);
  // A tuning in which not even the smallest m' fits is more likely a machine busy with
  // something else than its real speed; kept, it would hold every later run to that m'.
  if (!out.result.fits) {
    if (note)
      note("tuning not saved: not even m' " + std::to_string(out.result.chosen_modes) +
           " fits the budget (a busy machine?); the next run measures again");
    return out;
  }
  try {
    save_tuning(key, out.result);
    out.saved = true;
  } catch (const Error& e) {
    if (note) note(std::string("tuning not saved: ") + e.what());
  }
  return out;
}

EngineTuning tune_engine(QueryEngine& engine, const TuningKey& key, const std::vector<Pose>& poses, TuneOptions options,
                         bool retune, const std::function<void(const std::string&)>& note) {
  const std::size_t before = engine.modes();
  EngineTuning out =
      tune_and_keep(key, engine_query_timer(engine, poses, key.pace_hz), engine.max_modes(), options, retune, note);
  engine.set_modes(before);
  return out;
}

}  // namespace snapfit
