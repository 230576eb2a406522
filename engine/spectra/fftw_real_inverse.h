#pragma once
// Real-output inverse 3D FFT on the host through FFTW (single precision, all cores):
// f_j = sum_k H_k exp(+2 pi i k.j / N), unnormalized like engine/spectra/fft3d.h, from the half
// spectrum H (x = 0..nx/2, nx/2 + 1 complex values per row, x fastest) of a Hermitian H.
// Built only when CMake finds FFTW (SNAPFIT_HAVE_FFTW).
//
// Planned once per size with FFTW_MEASURE; FFTW's wisdom is cached under cache_root()
// (io/cache_file.h, written atomically), so a later process plans at once.
#include <array>
#include <complex>
#include <cstddef>
#include <string>
#include <vector>

namespace snapfit {

class FftwRealInverse {
 public:
  // `buffers` pairs of (half spectrum, real map) arrays, aligned for FFTW's SIMD.
  // Throws snapfit::Error naming the size when FFTW cannot plan it.
  FftwRealInverse(std::array<std::size_t, 3> dims, int buffers);
  ~FftwRealInverse();
  FftwRealInverse(const FftwRealInverse&) = delete;
  FftwRealInverse& operator=(const FftwRealInverse&) = delete;

  std::size_t half_count() const { return (dims_[0] / 2 + 1) * dims_[1] * dims_[2]; }
  std::size_t count() const { return dims_[0] * dims_[1] * dims_[2]; }
  std::complex<float>* half(int buffer) const { return halves_[std::size_t(buffer)]; }
  const float* real(int buffer) const { return reals_[std::size_t(buffer)]; }
  // real(buffer) = inverse FFT of half(buffer); half(buffer) is overwritten.
  void execute(int buffer) const;
  static std::string version();  // FFTW's version text

 private:
  std::array<std::size_t, 3> dims_;
  std::vector<std::complex<float>*> halves_;
  std::vector<float*> reals_;
  void* plan_ = nullptr;  // fftwf_plan
  void release();
};

}  // namespace snapfit
