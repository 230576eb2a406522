#pragma once
// Which device runs the haptic loop: the chosen device, tuned for the scene's frame
// budget (scheduler/tuning/engine_tuning.h), and, when the user did not name one, every other
// OpenCL device that passes its self-check (simulators such as Oclgrind excepted), each
// tuned the same way; the loop then runs on the pick of scheduler/tuning/device_choice.h
// loop_device. The others are left for background work.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/spectra/spectra.h"
#include "scheduler/modes/mode_tuning.h"
#include "scheduler/tuning/engine_tuning.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

struct TunedDevice {
  ComputeContext ctx;
  std::unique_ptr<QueryEngine> engine;
  TuningKey key;
  EngineTuning tuning;
};

struct LoopDeviceOptions {
  double margin = 0.25;                              // TuneOptions::margin
  bool retune = false;                               // measure even when the tuning file matches
  bool other_devices = true;                         // also tune the other devices
  TuneOptions tune;                                  // repetitions, progress
  std::function<void(const std::string&)> note;      // devices left out, tuning files not saved
  std::function<void(const DeviceInfo&)> on_start;   // before each device is tuned
  std::function<void(const TunedDevice&)> on_tuned;  // after
};

struct LoopDevices {
  std::vector<TunedDevice> devices;  // [0]: the chosen device
  std::size_t pick = 0;              // the one the loop runs on
  const TunedDevice& loop() const { return devices[pick]; }
};

// Tunes `ctx`'s device (and with options.other_devices every other one) for `variant`
// on `spectra`, and picks the loop's device. Throws snapfit::Error when the chosen
// device cannot be tuned; another device that fails is left out with a note.
LoopDevices tune_loop_devices(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                              const QueryVariant& variant, const LoopDeviceOptions& options);

// Makes the loop's device render `variant` instead: a new engine on it, tuned for the
// scene from the tuning file when one matches (as after scheduler/tuning/accuracy.h measured
// it; options.retune is ignored), else measured.
void use_variant_on_loop_device(LoopDevices& devices, const Scene& scene, const PairSpectra& spectra,
                                const QueryVariant& variant, const LoopDeviceOptions& options);

}  // namespace snapfit
