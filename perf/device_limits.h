#pragma once
// The device's limits for a roofline: memory bandwidth (a copy, strided and blocked
// reads of a 256 MiB buffer, blocked reads of a cache-sized block) and arithmetic peak
// (independent fma chains on float4, float8, float16), best of 5, with the kernels of
// kernels/device_limits.cl (built as the library builds its programs, through the program
// cache).
#include <CL/opencl.hpp>
#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/kernel_sources.h"
#include "engine/runtime/program_cache.h"
#include "perf/bench_common.h"

namespace snapfit::bench {

// The fma chains' length (-D ITERS).
constexpr int kFmaIters = 1024;

struct LimitResult {
  std::string name;
  double best = 0;  // GB/s or GFLOP/s
  std::vector<double> runs;
  std::string detail;
};

struct DeviceLimits {
  std::vector<LimitResult> bandwidth, compute;
  double bandwidth_gbs = 0, read_gbs = 0, peak_gflops = 0;
  double cached_gbs = 0, cached_mib = 0;  // reads of a buffer that fits in the last-level cache
  double buffer_mib = 0;
};

// Seconds of one kernel run (event profiling when the queue has it, else wall clock).
inline double time_kernel(const ComputeContext& ctx, cl::Kernel& k, std::size_t global) {
  cl::Event ev;
  const auto t0 = std::chrono::steady_clock::now();
  ctx.queue.enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), cl::NullRange, nullptr, &ev);
  ev.wait();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  try {
    const cl_ulong a = ev.getProfilingInfo<CL_PROFILING_COMMAND_START>();
    const cl_ulong b = ev.getProfilingInfo<CL_PROFILING_COMMAND_END>();
    if (b > a) return double(b - a) * 1e-9;
  } catch (const cl::Error&) {
  }
  return wall;
}

// Rates of kRuns timed runs of `k`: `amount` (bytes or flops) per second, in units of 1e9; and the best.
constexpr int kRuns = 5;
inline void time_runs(const ComputeContext& ctx, cl::Kernel& k, std::size_t global, double amount, LimitResult& r) {
  for (int i = 0; i < kRuns; ++i) {
    r.runs.push_back(amount / time_kernel(ctx, k, global) * 1e-9);
    r.best = std::max(r.best, r.runs.back());
  }
}

// Memory: a copy, strided and blocked reads of a 256 MiB buffer (less if the device
// cannot allocate it), then blocked reads of 6 MiB of it (about the query kernel's largest
// working set at m' = 32768), read 64 times per run (16 with `quick`).
inline void measure_memory(const ComputeContext& ctx, const cl::Program& program, bool quick, DeviceLimits& L) {
  std::size_t bytes = std::size_t(256) << 20;
  if (ctx.device.info.max_alloc_bytes > 0)
    bytes = std::min<std::size_t>(bytes, ctx.device.info.max_alloc_bytes / 4096 * 4096);
  const std::size_t n4 = bytes / 16;
  L.buffer_mib = double(bytes) / (1 << 20);
  std::vector<float> host(n4 * 4);
  for (std::size_t i = 0; i < host.size(); ++i) host[i] = float(i % 1024) * 1e-3f;
  cl::Buffer src(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, bytes, host.data());
  cl::Buffer dst(ctx.context, CL_MEM_READ_WRITE, bytes);
  const std::size_t strided_items = 65536, blocked_items = 1024;
  cl::Buffer partial(ctx.context, CL_MEM_READ_WRITE, sizeof(float) * strided_items);
  cl::Kernel copy(program, "copy_f4"), strided(program, "read_strided"), blocked(program, "read_blocked");
  set_args(copy, src, dst);
  set_args(strided, src, cl_uint(n4), partial);
  set_args(blocked, src, cl_uint(n4 / blocked_items), partial);
  struct Case {
    const char* name;
    cl::Kernel* k;
    std::size_t global;
    double bytes;
    const char* detail;
  };
  const Case cases[] = {
      {"copy", &copy, n4, 2.0 * double(bytes), "dst[i] = src[i] (float4): read + write counted, write-allocate not"},
      {"read_strided", &strided, strided_items, double(bytes), "65536 work-items, grid-stride float4 sums"},
      {"read_blocked", &blocked, blocked_items, double(bytes), "1024 work-items, contiguous float4 blocks"},
  };
  for (const Case& c : cases) {
    LimitResult r;
    r.name = c.name;
    r.detail = c.detail;
    time_kernel(ctx, *c.k, c.global);  // warm-up (first touch, page mapping)
    time_runs(ctx, *c.k, c.global, c.bytes, r);
    if (r.name == "copy")
      L.bandwidth_gbs = std::max(L.bandwidth_gbs, r.best);
    else
      L.read_gbs = std::max(L.read_gbs, r.best);
    L.bandwidth.push_back(r);
  }
  L.bandwidth_gbs = std::max(L.bandwidth_gbs, L.read_gbs);
  const std::size_t small4 = (std::size_t(6) << 20) / 16, reps = quick ? 16 : 64;
  cl::Kernel cached(program, "read_blocked_repeat");
  set_args(cached, src, cl_uint(small4 / blocked_items), cl_uint(reps), partial);
  LimitResult r;
  r.name = "read_cached";
  r.detail = "6 MiB of the buffer, contiguous blocks, read " + std::to_string(reps) + " times";
  time_kernel(ctx, cached, blocked_items);
  time_runs(ctx, cached, blocked_items, double(small4 * 16 * reps), r);
  L.cached_gbs = r.best;
  L.cached_mib = 6;
  L.bandwidth.push_back(r);
}

// Arithmetic: the work of each fma kernel grown until one run takes >= 0.1 s (0.03 s
// with `quick`).
inline void measure_arithmetic(const ComputeContext& ctx, const cl::Program& program, bool quick, DeviceLimits& L) {
  for (const auto& [name, width] :
       std::vector<std::pair<std::string, int>>{{"fma_f4", 4}, {"fma_f8", 8}, {"fma_f16", 16}}) {
    cl::Kernel k(program, name.c_str());
    set_args(k, 0.9999f, 1e-4f);  // argument 2, the output, below
    std::size_t global = 4096;
    const double target = quick ? 0.03 : 0.1;
    cl::Buffer out;
    double s = 0;
    while (true) {
      out = cl::Buffer(ctx.context, CL_MEM_WRITE_ONLY, sizeof(float) * global);
      k.setArg(2, out);
      s = time_kernel(ctx, k, global);
      if (s >= target || global >= (std::size_t(1) << 26)) break;
      global *= std::clamp<std::size_t>(std::size_t(target / std::max(s, 1e-6)) + 1, 2, 64);
    }
    LimitResult r;
    r.name = name;
    r.detail = std::to_string(global) + " work-items x " + std::to_string(kFmaIters) +
               " iterations x 8 chains x float" + std::to_string(width) + " fma (2 flops per lane)";
    time_runs(ctx, k, global, double(global) * kFmaIters * 8 * width * 2, r);
    L.peak_gflops = std::max(L.peak_gflops, r.best);
    L.compute.push_back(r);
  }
}

// Measures the limits; `quick` shortens the cache reads and the arithmetic runs.
inline DeviceLimits measure_limits(const ComputeContext& ctx, bool quick) {
  const cl::Program program = build_program(ctx, "device_limits", kernel_source("device_limits"),
                                            "-cl-std=CL1.2 -D ITERS=" + std::to_string(kFmaIters))
                                  .program;
  DeviceLimits L;
  measure_memory(ctx, program, quick, L);
  measure_arithmetic(ctx, program, quick, L);
  return L;
}

}  // namespace snapfit::bench
