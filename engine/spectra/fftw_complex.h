#pragma once
// Complex 3D FFT on the host through FFTW (single precision, all cores), in place, with
// Fft3d's conventions (engine/spectra/fft3d.h): forward X_k = sum_j x_j exp(-2 pi i k.j / N),
// inverse unnormalized, x fastest. For transforms done a few times (the spectra, the near
// part's nodes): planned with FFTW_ESTIMATE, no measuring. Built only when CMake finds
// FFTW (SNAPFIT_HAVE_FFTW).
#include <array>
#include <complex>
#include <cstddef>
#include <vector>

namespace snapfit {

// Throws snapfit::Error naming the size when `data` does not hold dims' points or FFTW
// cannot plan it.
void fftw_complex_in_place(std::vector<std::complex<float>>& data, const std::array<std::size_t, 3>& dims,
                           bool inverse);

}  // namespace snapfit
