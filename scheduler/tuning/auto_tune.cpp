// auto_tune (include/snapfit/tuning.h): the scene's engine tuned through the tuning
// file, on the poses of the scene's trajectory (scheduler/tuning/engine_tuning.h).
#include "pipeline/assembly_access.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/tuning/engine_tuning.h"
#include "snapfit/assembly.h"
#include "snapfit/tuning.h"

namespace snapfit {

TuningResult auto_tune(const Assembly& assembly, QueryEngine& engine, const AutoTuneOptions& options) {
  const Scene& scene = assembly.scene();
  const TuningKey key =
      tuning_key_for(AssemblyAccess::context(assembly).device.info, engine.variant(),
                     AssemblyAccess::pair(assembly).spectra, scene.frame_budget_ms, options.margin, scene.loop_rate_hz);
  TuneOptions sweep;
  sweep.repetitions = options.repetitions;
  sweep.progress = options.progress;
  EngineTuning tuned = tune_engine(engine, key, tuning_poses(scene), sweep, options.retune, options.note);
  tuned.result.file = tuned.from_file || tuned.saved ? tuned.path : "";
  return tuned.result;
}

}  // namespace snapfit
