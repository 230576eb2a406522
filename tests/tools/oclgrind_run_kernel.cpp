// Runs a one-kernel OpenCL file on Oclgrind's device, for the reproducer of
// tests/data/oclgrind (tests/oclgrind/test_oclgrind_reproducer.cpp):
//   oclgrind_run_kernel FILE
// builds FILE, runs its kernel k(__global const float4* in, __global float* out) over 4
// work-items with in[i] = (i + 1, 0, 0, 0) for i < 8, and prints out[0] .. out[3]. The
// checks are Oclgrind's environment (OCLGRIND_UNINITIALIZED and the rest).
#include <fstream>
#include <iostream>
#include <sstream>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/runtime/program_cache.h"
#include "snapfit/error.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: oclgrind_run_kernel FILE\n";
    return 2;
  }
  try {
    std::ifstream file(argv[1]);
    if (!file) throw snapfit::Error(std::string("cannot read ") + argv[1]);
    std::stringstream source;
    source << file.rdbuf();
    const snapfit::ComputeContext ctx = snapfit::make_compute_context(snapfit::select_device("oclgrind"));
    snapfit::ProgramCacheConfig no_cache;
    const cl::Program program = snapfit::build_program(ctx, "k", source.str(), "-cl-std=CL1.2", no_cache).program;
    std::vector<cl_float4> in(8, cl_float4{{0, 0, 0, 0}});
    for (std::size_t i = 0; i < in.size(); ++i) in[i].s[0] = static_cast<float>(i + 1);
    cl::Buffer in_buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * in.size(),
                         in.data());
    cl::Buffer out_buffer(ctx.context, CL_MEM_WRITE_ONLY, sizeof(float) * 4);
    cl::Kernel kernel(program, "k");
    kernel.setArg(0, in_buffer);
    kernel.setArg(1, out_buffer);
    ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(4), cl::NullRange);
    float out[4];
    ctx.queue.enqueueReadBuffer(out_buffer, CL_TRUE, 0, sizeof(out), out);
    for (float v : out) std::cout << v << "\n";
  } catch (const std::exception& e) {
    std::cerr << "oclgrind_run_kernel: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
