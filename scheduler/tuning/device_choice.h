#pragma once
// Heterogeneous devices: with several OpenCL devices, the haptic loop runs on
// the one with the lowest tuned latency; the others are left for background work.
#include <vector>

#include "scheduler/modes/mode_tuning.h"

namespace snapfit {

// The index of the tuning with the lowest latency: the lowest measured p99 at the
// largest m' every candidate measured; without a common level, the largest chosen m'.
// Candidates that do not fit the budget lose to any that do. Throws snapfit::Error
// when `tunings` is empty.
std::size_t lowest_latency(const std::vector<TuningResult>& tunings);

// The device the haptic loop runs on. Among the tunings that fit the budget (all, if
// none does), those whose chosen m' is at least half the largest chosen m'; of those,
// the devices that run kernels in the calling thread when there are any
// (`in_caller_thread`, DeviceInfo::runs_in_caller_thread: PoCL's basic driver, with no
// worker thread to wake each frame, so fewer late frames at the same m': docs/haptics.md
// has the figures); then the lowest latency (lowest_latency). Throws
// snapfit::Error when `tunings` is empty or the flags do not match it.
std::size_t loop_device(const std::vector<TuningResult>& tunings, const std::vector<bool>& in_caller_thread);

}  // namespace snapfit
