#pragma once
// Heterogeneous devices (issue 5): with several OpenCL devices, the haptic loop runs on
// the one with the lowest tuned latency; the others are left for background work.
#include <vector>

#include "scheduler/auto_tune.h"

namespace snapfit {

// The index of the tuning with the lowest latency: the lowest measured p99 at the
// largest m' every candidate measured; without a common level, the largest chosen m'.
// Candidates that do not fit the budget lose to any that do. Throws snapfit::Error
// when `tunings` is empty.
std::size_t lowest_latency(const std::vector<TuningResult>& tunings);

}  // namespace snapfit
