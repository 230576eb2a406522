#pragma once
// A host, double-precision evaluation of the per-pose sum of include/snapfit/query.h (seed
// 000 eq. 10-12) from the same spectra: every retained mode accumulated in double, the
// spectra of part 2 interpolated in double with the same schemes. No OpenCL. It is the
// reference for accuracy reports (perf/bench_accuracy: all modes, no truncation) and
// for checking the device kernel's float accumulation at the same m'.
#include <cstddef>
#include <vector>

#include "engine/spectra/mode_order.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

struct ReferenceOptions {
  Interpolation interpolation = Interpolation::tricubic;
  std::size_t modes = 0;  // m': the first modes of mode_order (engine/spectra/mode_order.h); 0 = every mode
  bool force = true;
  bool torque = true;  // the derivative of the interpolated energy under rotation
};

// The result for part 2 at `pose` in part 1's frame, with the engine's frames, signs
// and flags (query_outside_grid, query_bad_pose). `order` may be passed to avoid
// re-sorting (it must be mode_order(spectra)). Parallel over modes on TBB, with a
// deterministic reduction.
QueryResult reference_query(const PairSpectra& spectra, const Pose& pose, const ReferenceOptions& options = {},
                            const std::vector<std::size_t>* order = nullptr);

}  // namespace snapfit
