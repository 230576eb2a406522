#pragma once
// A 3D FFT of a box of values in host memory, in place, with Fft3d's conventions
// (engine/spectra/fft3d.h): on the host through FFTW for a CPU device, where it is faster
// and compiles no OpenCL program (clFFT's kernels take PoCL tens of seconds per size the
// first time), else on the device through clFFT. For transforms made a few times, not
// per frame.
#include <array>
#include <complex>
#include <memory>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/spectra/fft3d.h"

namespace snapfit {

// automatic: the host (when FFTW is built) for a CPU device, else the device.
enum class FftPlace { automatic, device, host };

class BoxFft {
 public:
  // Throws snapfit::Error for `host` in a build without FFTW, or as Fft3d.
  BoxFft(const FftLibrary& library, const ComputeContext& ctx, std::array<std::size_t, 3> dims,
         FftPlace place = FftPlace::automatic);
  bool on_host() const { return !device_; }
  std::array<std::size_t, 3> dims() const { return dims_; }
  // box holds dims' points, x fastest.
  void transform(FftDirection direction, std::vector<std::complex<float>>& box) const;

 private:
  const ComputeContext& ctx_;
  std::array<std::size_t, 3> dims_;
  std::unique_ptr<Fft3d> device_;  // clFFT's plan, on the device path only
};

}  // namespace snapfit
