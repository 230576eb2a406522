#pragma once
// Complex-to-complex inverse 3D FFT on the OpenCL device through VkFFT (D. Tolmachev,
// "VkFFT - A Performant, Cross-Platform and Open-Source GPU FFT Library", IEEE Access 11,
// 2023; Debian libvkfft-dev, header-only, its OpenCL backend): f_j = sum_k P_k
// exp(+2 pi i k.j / N), unnormalized like engine/spectra/fft3d.h, interleaved complex float, x
// fastest. A third inverse of the full maps (engine/maps/map_fft.h, MapFft::vkfft), built only
// when CMake finds vkFFT.h (SNAPFIT_HAVE_VKFFT). VkFFT generates and compiles its kernels
// for the size when planned, outside snapfit's program cache.
#include <CL/opencl.hpp>
#include <array>
#include <cstddef>
#include <memory>
#include <string>

#include "engine/runtime/compute_context.h"

namespace snapfit {

class VkfftInverse {
 public:
  // Plans `batch` inverses of dims points each on ctx's device and queue, reading
  // `spectrum` and writing `map` (buffers of batch x dims complex floats, one transform
  // after the other; others of that size may be passed to enqueue). Throws snapfit::Error
  // naming the size and the device when VkFFT cannot.
  VkfftInverse(const ComputeContext& ctx, std::array<std::size_t, 3> dims, const cl::Buffer& spectrum,
               const cl::Buffer& map, std::size_t batch = 1);
  ~VkfftInverse();
  VkfftInverse(const VkfftInverse&) = delete;
  VkfftInverse& operator=(const VkfftInverse&) = delete;

  // Enqueues the transform of `spectrum` into `map` on the context's in-order queue and
  // returns at once (later commands see the map). `spectrum` is overwritten (VkFFT works in it).
  void enqueue(const cl::Buffer& spectrum, const cl::Buffer& map);
  static std::string version();  // "1.2.26"

 private:
  struct Plan;
  std::unique_ptr<Plan> plan_;
};

}  // namespace snapfit
