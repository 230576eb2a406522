#pragma once
// Runs kernels/device_check.cl on a device and compares with a double-precision host
// reference: proves the device builds snapfit's kernels and computes correctly.
#include <string>

#include "engine/runtime/program_cache.h"

namespace snapfit {

struct DeviceCheckResult {
  bool passed = false;
  std::string precision;      // "float" or "double"
  double relative_error = 0;  // |device - reference| / |reference| of the total sum
  double tolerance = 0;
  ProgramOrigin origin = ProgramOrigin::compiled;
  double build_ms = 0;
  double kernel_ms = 0;  // from the OpenCL event's profiling counters
};

// `use_double` requires fp64 (throws snapfit::Error naming the device otherwise).
// `points`: work-items, each one term of the sum (fewer for a simulator, which runs them
// one at a time).
DeviceCheckResult run_device_check(const ComputeContext& ctx, bool use_double,
                                   const ProgramCacheConfig& cache = default_program_cache(), int points = 100000);

}  // namespace snapfit
