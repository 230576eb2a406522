#include "engine/runtime/compute_context.h"

#include "snapfit/error.h"

namespace snapfit {

ComputeContext make_compute_context(const Device& device) {
  try {
    ComputeContext ctx{device, cl::Context(device.device), cl::CommandQueue()};
    ctx.queue = cl::CommandQueue(ctx.context, device.device, CL_QUEUE_PROFILING_ENABLE);
    return ctx;
  } catch (const cl::Error& e) {
    throw Error("cannot open OpenCL device " + device.info.name + ": " + e.what() + " (error " +
                std::to_string(e.err()) + ")");
  }
}

void throw_device_error(const std::string& what, const std::string& device_name, const cl::Error& e) {
  throw Error(what + " on " + device_name + ": " + e.what() + " (error " + std::to_string(e.err()) + ")");
}

}  // namespace snapfit
