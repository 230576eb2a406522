#include "scheduler/tuning/loop_devices.h"

#include "engine/query/query_engine.h"
#include "engine/runtime/device_check.h"
#include "scheduler/tuning/device_choice.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

TunedDevice tune_device(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                        const QueryVariant& variant, const std::vector<Pose>& poses, const LoopDeviceOptions& options) {
  if (options.on_start) options.on_start(ctx.device.info);
  TunedDevice out{ctx, make_query_engine(ctx, spectra, variant), {}, {}};
  out.key =
      tuning_key_for(ctx.device.info, variant, spectra, scene.frame_budget_ms, options.margin, scene.loop_rate_hz);
  out.tuning = tune_engine(*out.engine, out.key, poses, options.tune, options.retune, options.note);
  if (options.on_tuned) options.on_tuned(out);
  return out;
}

}  // namespace

LoopDevices tune_loop_devices(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                              const QueryVariant& variant, const LoopDeviceOptions& options) {
  const std::vector<Pose> poses = tuning_poses(scene);
  LoopDevices out;
  out.devices.push_back(tune_device(ctx, scene, spectra, variant, poses, options));
  if (options.other_devices)
    for (const Device& other : enumerate_devices()) {
      if (other.info.index == ctx.device.info.index) continue;
      if (other.info.is_simulator()) {
        // Oclgrind interprets kernels for checks; it could never hold a haptic frame.
        if (options.note) options.note("device " + other.info.name + " is a simulator; left out of the loop choice");
        continue;
      }
      try {
        const ComputeContext other_ctx = make_compute_context(other);
        if (!run_device_check(other_ctx, false).passed) {
          if (options.note)
            options.note("device " + other.info.name + " failed its self-check; left out of the loop choice");
          continue;
        }
        out.devices.push_back(tune_device(other_ctx, scene, spectra, variant, poses, options));
      } catch (const Error& e) {
        if (options.note) options.note("device " + other.info.name + " left out of the loop choice: " + e.what());
      }
    }
  std::vector<TuningResult> tunings;
  std::vector<bool> in_caller_thread;
  for (const TunedDevice& d : out.devices) {
    tunings.push_back(d.tuning.result);
    in_caller_thread.push_back(d.ctx.device.info.runs_in_caller_thread());
  }
  out.pick = loop_device(tunings, in_caller_thread);
  return out;
}

void use_variant_on_loop_device(LoopDevices& devices, const Scene& scene, const PairSpectra& spectra,
                                const QueryVariant& variant, const LoopDeviceOptions& options) {
  TunedDevice& loop = devices.devices[devices.pick];
  const ComputeContext ctx = loop.ctx;
  loop.engine.reset();  // one engine per device at a time: free its buffers first
  // Measured just before for the choice: read back from the tuning file, not re-measured.
  LoopDeviceOptions reuse = options;
  reuse.retune = false;
  reuse.on_start = nullptr;
  loop = tune_device(ctx, scene, spectra, variant, tuning_poses(scene), reuse);
}

}  // namespace snapfit
