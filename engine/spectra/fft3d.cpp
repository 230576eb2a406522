#include "engine/spectra/fft3d.h"

#include <clFFT.h>
#include <fcntl.h>
#include <string>
#include <unistd.h>

#include "snapfit/error.h"

namespace snapfit {
namespace {

std::string dims_text(const std::array<std::size_t, 3>& d) {
  return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]);
}

bool only_fast_factors(std::size_t n) {
  if (n == 0) return false;
  for (std::size_t p : {2, 3, 5, 7})
    while (n % p == 0) n /= p;
  return n == 1;
}

// PoCL's compiler prints "N warnings generated." for clFFT's generated kernels while a
// plan bakes; this hides stderr for that call only (clFFT still returns its status).
struct QuietStderr {
  int saved = ::dup(2);
  QuietStderr() {
    const int null = ::open("/dev/null", O_WRONLY);
    if (null >= 0 && saved >= 0) ::dup2(null, 2);
    if (null >= 0) ::close(null);
  }
  ~QuietStderr() {
    if (saved >= 0) {
      ::dup2(saved, 2);
      ::close(saved);
    }
  }
};

void check(clfftStatus status, const std::string& what) {
  if (status != CLFFT_SUCCESS) throw Error(what + " (clFFT status " + std::to_string(static_cast<int>(status)) + ")");
}

}  // namespace

std::size_t next_fft_size(std::size_t n) {
  std::size_t m = std::max<std::size_t>(n, 1);
  while (!only_fast_factors(m)) ++m;
  return m;
}

std::size_t next_even_fft_size(std::size_t n) {
  std::size_t m = next_fft_size(n);
  while (m % 2) m = next_fft_size(m + 1);
  return m;
}

FftLibrary::FftLibrary() {
  clfftSetupData setup;
  check(clfftInitSetupData(&setup), "clFFT set-up failed");
  check(clfftSetup(&setup), "clFFT set-up failed");
}

FftLibrary::~FftLibrary() { clfftTeardown(); }

Fft3d::Fft3d(const FftLibrary&, const ComputeContext& ctx, std::array<std::size_t, 3> dims, std::size_t batch)
    : ctx_(ctx), dims_(dims), batch_(batch) {
  for (std::size_t n : dims)
    if (!only_fast_factors(n))
      throw Error("FFT size " + dims_text(dims) + " has a factor other than 2, 3, 5, 7; use next_fft_size");
  if (batch == 0) throw Error("FFT size " + dims_text(dims) + ": a batch of 0 transforms");
  const std::string where = "FFT plan " + dims_text(dims) + " on " + ctx.device.info.name;
  clfftPlanHandle plan = 0;
  std::size_t lengths[3] = {dims[0], dims[1], dims[2]};
  check(clfftCreateDefaultPlan(&plan, ctx.context(), CLFFT_3D, lengths), where + ": cannot create");
  plan_ = plan;
  try {
    check(clfftSetPlanPrecision(plan, CLFFT_SINGLE), where);
    check(clfftSetLayout(plan, CLFFT_COMPLEX_INTERLEAVED, CLFFT_COMPLEX_INTERLEAVED), where);
    check(clfftSetResultLocation(plan, CLFFT_OUTOFPLACE), where);
    check(clfftSetPlanScale(plan, CLFFT_BACKWARD, 1.0f), where);  // unnormalized inverse (eq. 14 without 1/N)
    if (batch > 1) {
      check(clfftSetPlanBatchSize(plan, batch), where + ": batch of " + std::to_string(batch));
      check(clfftSetPlanDistance(plan, count(), count()), where);
    }
    cl_command_queue queue = ctx.queue();
    clfftStatus baked;
    {
      QuietStderr quiet;
      baked = clfftBakePlan(plan, 1, &queue, nullptr, nullptr);
    }
    check(baked, where + ": cannot bake");
  } catch (...) {
    clfftDestroyPlan(&plan);
    throw;
  }
}

Fft3d::~Fft3d() {
  clfftPlanHandle plan = plan_;
  clfftDestroyPlan(&plan);
}

void Fft3d::transform(FftDirection direction, const cl::Buffer& input, const cl::Buffer& output) const {
  enqueue(direction, input, output);
  ctx_.queue.finish();
}

void Fft3d::enqueue(FftDirection direction, const cl::Buffer& input, const cl::Buffer& output) const {
  cl_command_queue queue = ctx_.queue();
  cl_mem in = input(), out = output();
  check(clfftEnqueueTransform(plan_, direction == FftDirection::forward ? CLFFT_FORWARD : CLFFT_BACKWARD, 1, &queue, 0,
                              nullptr, nullptr, &in, &out, nullptr),
        "FFT " + dims_text(dims_) + " failed on " + ctx_.device.info.name);
}

}  // namespace snapfit
