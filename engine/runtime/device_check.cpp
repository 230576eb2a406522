#include "engine/runtime/device_check.h"

#include <cmath>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/kernel_sources.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

template <typename Real>
DeviceCheckResult check(const ComputeContext& ctx, const ProgramCacheConfig& cache, const int n) {
  constexpr bool is_double = sizeof(Real) == 8;
  // Largest power-of-two work-group size the device allows, at most 256.
  std::size_t wg = 1;
  while (wg * 2 <= std::min<std::size_t>(256, ctx.device.info.max_work_group_size)) wg *= 2;
  const int groups = static_cast<int>((n + wg - 1) / wg);

  // Reference in long double; `scale` bounds the size of every intermediate of a term.
  std::vector<Real> x(n);
  long double reference = 0.0L;
  double scale = 0.0;
  for (int i = 0; i < n; ++i) {
    x[i] = static_cast<Real>(-2.0 + 4.0 * i / (n - 1));
    const long double v = static_cast<long double>(x[i]);
    reference += (2.0L * v - 3.0L) * v + 1.0L + std::sin(v);
    scale += static_cast<double>(2.0L * v * v + 3.0L * std::abs(v) + 2.0L);
  }

  const std::string options =
      std::string("-D REAL=") + (is_double ? "double -D SNAPFIT_FP64" : "float") + " -D WG_SIZE=" + std::to_string(wg);
  DeviceCheckResult result;
  result.precision = is_double ? "double" : "float";
  const BuiltProgram built = build_program(ctx, "device_check", kernel_source("device_check"), options, cache);
  result.origin = built.origin;
  result.build_ms = built.build_ms;

  try {
    cl::Buffer x_buf(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Real) * n, x.data());
    cl::Buffer sums_buf(ctx.context, CL_MEM_WRITE_ONLY, sizeof(Real) * groups);
    cl::Kernel kernel(built.program, "device_check");
    kernel.setArg(0, x_buf);
    kernel.setArg(1, sums_buf);
    kernel.setArg(2, n);
    cl::Event event;
    ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(groups * wg), cl::NDRange(wg), nullptr, &event);
    std::vector<Real> sums(groups);
    ctx.queue.enqueueReadBuffer(sums_buf, CL_TRUE, 0, sizeof(Real) * groups, sums.data());
    result.kernel_ms =
        (event.getProfilingInfo<CL_PROFILING_COMMAND_END>() - event.getProfilingInfo<CL_PROFILING_COMMAND_START>()) *
        1e-6;
    double total = 0.0;
    for (Real s : sums) total += static_cast<double>(s);
    // Tolerance: each term is a few roundings (sin: <= 4 ulp in OpenCL C), and each
    // partial sum passes through log2(wg) additions on the device and one on the host:
    // |error| <= eps * (8 + log2(wg)) * sum of |intermediates| (scale).
    const double eps = is_double ? 1.1e-16 : 6.0e-8;
    const double ref = static_cast<double>(reference);
    result.tolerance = eps * (8.0 + std::log2(static_cast<double>(wg))) * scale / std::abs(ref);
    result.relative_error = std::abs(total - ref) / std::abs(ref);
    result.passed = std::isfinite(total) && result.relative_error <= result.tolerance;
  } catch (const cl::Error& e) {
    throw_device_error("device check failed", ctx.device.info.name, e);
  }
  return result;
}

}  // namespace

DeviceCheckResult run_device_check(const ComputeContext& ctx, bool use_double, const ProgramCacheConfig& cache,
                                   int points) {
  if (points < 2) throw Error("the device check needs at least 2 points (got " + std::to_string(points) + ")");
  if (!use_double) return check<float>(ctx, cache, points);
  if (!ctx.device.info.fp64) throw Error("device " + ctx.device.info.name + " has no double precision (cl_khr_fp64)");
  return check<double>(ctx, cache, points);
}

}  // namespace snapfit
