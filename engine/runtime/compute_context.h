#pragma once
// The OpenCL objects every stage shares for one device: context and in-order queue.
#include "engine/runtime/device.h"

namespace snapfit {

struct ComputeContext {
  Device device;
  cl::Context context;
  cl::CommandQueue queue;  // in-order, profiling enabled (timings come from events)
};

// Throws snapfit::Error naming the device when the context or queue cannot be made.
ComputeContext make_compute_context(const Device& device);

// An OpenCL error as snapfit::Error: "<what> on <device>: <OpenCL call> (error <code>)".
[[noreturn]] void throw_device_error(const std::string& what, const std::string& device_name, const cl::Error& e);

}  // namespace snapfit
