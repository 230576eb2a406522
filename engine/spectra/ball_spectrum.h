#pragma once
// Spectra of unions of balls (seed 001 sec. 2.5): the density f = sum_j 1_{B(x_j, r_j)},
// whose Fourier transform is analytic,
//   f^(w) = sum_j Bhat(r_j, |w|) exp(-2 pi i w.x_j),
//   Bhat(r, q) = (4/3) pi r^3 * 3 (sin t - t cos t) / t^3,  t = 2 pi q r
// (= 4 pi r^3 j1(t) / t, j1 the spherical Bessel function), on the engine's frequency
// lattice w_k = k' / L (engine/spectra/spectra.h), "centred" at c: S(w) = f^(w) exp(2 pi i w.c).
// f's 0-superlevel set is the union (seed 001 eq. 2); for disjoint balls f is its indicator.
//
// Three ways to the same numbers:
// - ball_spectrum_reference: the sum in double on the host (the tests' reference);
// - ball_spectrum_direct: the sum on the OpenCL device, one work item per mode
//   (kernels/ball_ndft.cl), O(modes * balls): for few balls or few modes (m');
// - ball_spectrum_nufft: a type-1 non-uniform FFT. Bhat depends on r_j, so the radii
//   are interpolated at Chebyshev nodes r_p, Bhat(r_j, q) ~ sum_p l_p(r_j) Bhat(r_p, q),
//   and each node's weights l_p(r_j) are spread with the ES kernel (engine/spectra/es_kernel.h)
//   onto a 2x oversampled periodic grid, transformed with the engine's FFT and
//   deconvolved by the kernel's transform: O(P (balls w^3 + n log n)).
#include <Eigen/Core>
#include <array>
#include <complex>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/spectra/fft3d.h"
#include "engine/runtime/program_cache.h"
#include "engine/fields/sphere_decomposition.h"

namespace snapfit {

// The lattice: dims (FFT order, negative k' wrapped), periods L, and the centre c.
struct FrequencyLattice {
  std::array<std::size_t, 3> dims{};
  Eigen::Vector3d length = Eigen::Vector3d::Ones();
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  std::size_t count() const { return dims[0] * dims[1] * dims[2]; }
};

// Bhat(r, q) in double (a series for small t).
double ball_transform(double radius, double q);

// Signed mode indices (k'_x, k'_y, k'_z) of every lattice node, in FFT order.
std::vector<std::array<int, 3>> lattice_modes(const FrequencyLattice& lattice);

// S at the listed modes, in double.
std::vector<std::complex<double>> ball_spectrum_reference(const std::vector<Ball>& balls,
                                                          const FrequencyLattice& lattice,
                                                          const std::vector<std::array<int, 3>>& modes);

// S at the listed modes (empty: every lattice node, FFT order) on the device.
// Throws snapfit::Error naming the device on a device failure.
std::vector<std::complex<float>> ball_spectrum_direct(const ComputeContext& ctx, const std::vector<Ball>& balls,
                                                      const FrequencyLattice& lattice,
                                                      const std::vector<std::array<int, 3>>& modes = {},
                                                      const ProgramCacheConfig& cache = default_program_cache());

struct BallNufftOptions {
  double tolerance = 1e-5;  // relative to sum_j Bhat(r_j, 0): sets the kernel width and the radius nodes
  double oversampling = 2.0;
};

struct BallNufftStats {
  int radius_nodes = 0;  // P
  int kernel_width = 0;
  std::array<std::size_t, 3> fine_dims{};
};

// S at every lattice node, FFT order. Throws snapfit::Error for no balls, a tolerance
// outside (0, 0.1], oversampling below 2, or a device failure.
std::vector<std::complex<float>> ball_spectrum_nufft(const FftLibrary& library, const ComputeContext& ctx,
                                                     const std::vector<Ball>& balls, const FrequencyLattice& lattice,
                                                     const BallNufftOptions& options = {},
                                                     BallNufftStats* stats = nullptr);

}  // namespace snapfit
