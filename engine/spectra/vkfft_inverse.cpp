#include "engine/spectra/vkfft_inverse.h"

#include <cstdint>
#include <vkFFT.h>

#include "snapfit/error.h"

namespace snapfit {
namespace {

std::string dims_text(const std::array<std::size_t, 3>& d) {
  return std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " + std::to_string(d[2]);
}

}  // namespace

// VkFFT keeps pointers to the handles and sizes it was configured with: they live here.
struct VkfftInverse::Plan {
  VkFFTApplication app{};
  cl_device_id device = nullptr;
  cl_context context = nullptr;
  cl_command_queue queue = nullptr;
  cl_mem spectrum = nullptr, map = nullptr;
  std::uint64_t bytes = 0;
  std::string device_name;
  bool initialized = false;
};

VkfftInverse::VkfftInverse(const ComputeContext& ctx, std::array<std::size_t, 3> dims, const cl::Buffer& spectrum,
                           const cl::Buffer& map, std::size_t batch)
    : plan_(std::make_unique<Plan>()) {
  Plan& p = *plan_;
  p.device = ctx.device.device();
  p.context = ctx.context();
  p.queue = ctx.queue();
  p.spectrum = spectrum();
  p.map = map();
  p.bytes = std::uint64_t(2 * sizeof(float)) * dims[0] * dims[1] * dims[2] * batch;
  p.device_name = ctx.device.info.name;
  VkFFTConfiguration c{};
  c.FFTdim = 3;
  for (int a = 0; a < 3; ++a) c.size[a] = dims[std::size_t(a)];
  c.numberBatches = batch;
  c.device = &p.device;
  c.context = &p.context;
  c.commandQueue = &p.queue;
  // Out of place: the spectrum in VkFFT's `buffer`, the map in its `inputBuffer`; the
  // inverse returns from the first to the second (as perf/bench_fft.cpp measures it).
  c.bufferSize = &p.bytes;
  c.inputBufferSize = &p.bytes;
  c.buffer = &p.spectrum;
  c.inputBuffer = &p.map;
  c.isInputFormatted = 1;
  c.inverseReturnToInputBuffer = 1;
  c.normalize = 0;
  const VkFFTResult r = initializeVkFFT(&p.app, c);
  if (r != VKFFT_SUCCESS)
    throw Error("VkFFT cannot plan the " + dims_text(dims) + " inverse FFT (batch of " + std::to_string(batch) +
                ") on " + p.device_name + " (VkFFTResult " + std::to_string(int(r)) + ")");
  p.initialized = true;
}

VkfftInverse::~VkfftInverse() {
  if (plan_ && plan_->initialized) deleteVkFFT(&plan_->app);
}

void VkfftInverse::enqueue(const cl::Buffer& spectrum, const cl::Buffer& map) {
  Plan& p = *plan_;
  cl_mem in = spectrum(), out = map();
  VkFFTLaunchParams launch{};
  launch.commandQueue = &p.queue;
  launch.buffer = &in;
  launch.inputBuffer = &out;
  const VkFFTResult r = VkFFTAppend(&p.app, 1, &launch);
  if (r != VKFFT_SUCCESS)
    throw Error("VkFFT's inverse FFT failed on " + p.device_name + " (VkFFTResult " + std::to_string(int(r)) + ")");
}

std::string VkfftInverse::version() {
  const int v = VkFFTGetVersion();
  return std::to_string(v / 10000) + "." + std::to_string(v / 100 % 100) + "." + std::to_string(v % 100);
}

}  // namespace snapfit
