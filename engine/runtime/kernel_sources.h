#pragma once
// OpenCL C sources of kernels/*.cl, embedded at build time (cmake/EmbedKernels.cmake).
#include <string>
#include <vector>

namespace snapfit {

struct KernelSource {
  const char* name;  // file name without ".cl"
  const char* text;
};

// Every embedded source, in file-name order.
const std::vector<KernelSource>& embedded_kernel_sources();

// The source named `name` ("device_check" for kernels/device_check.cl); throws
// snapfit::Error listing the known names when there is none.
std::string kernel_source(const std::string& name);

}  // namespace snapfit
