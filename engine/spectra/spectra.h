#pragma once
// Fourier spectra of both parts' affinity fields (seed 000 eq. 8, 13; docs/design.md
// "Correlation in the Fourier domain"), on one common zero-padded FFT grid so both
// parts share the frequency nodes w_k = k / L (L_a = dims_a * h per axis).
//
// Continuous transform: rho^(w) = integral rho(p) exp(-2 pi i w.p) dV. Sampled at the
// grid points p_i = o + h i, rho^(w_k) = h^3 exp(-2 pi i w_k.o) DFT(rho)[k].
// Each part's spectrum is stored "centred": S(w) = rho^(w) exp(+2 pi i w.c), c the
// centre of the part's padded FFT box, which removes the fast phase oscillation that
// an off-centre support gives, so S interpolates well at rotated frequencies.
#include <Eigen/Core>
#include <array>
#include <complex>
#include <functional>
#include <memory>
#include <vector>

#include "engine/fields/descriptors.h"
#include "engine/spectra/box_fft.h"
#include "engine/spectra/es_kernel.h"
#include "engine/spectra/fft3d.h"

namespace snapfit {

using Complex = std::complex<float>;

struct SpectrumOptions {
  // Each padded FFT axis holds at least oversampling * (points of the larger part):
  // zero padding in space oversamples the spectrum, which the rotation interpolation needs.
  double oversampling = 2.0;
  // Also part 2's deconvolved spectrum (PartSpectrum::deconvolved), which evaluates S2
  // exactly at rotated frequencies with this kernel (engine/spectra/es_kernel.h; 5: ~1e-4, 7: ~1e-6); 0:
  // not computed (a part that never rotates).
  int exact_rotation_width = 5;
  // Where the forward FFTs run (engine/spectra/box_fft.h).
  FftPlace fft = FftPlace::automatic;
};

struct PartSpectrum {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();       // c, in the part's own frame
  Eigen::Vector3d half_extent = Eigen::Vector3d::Zero();  // samples lie within c +- this
  std::vector<Complex> rho;                               // S(w_k), FFT order (k_x fastest, negative k wrapped)
  // Part 2 only, with SpectrumOptions::exact_rotation_width: the spectrum of the samples
  // divided by the kernel's transform at their offset from c (engine/spectra/es_kernel.h), from
  // which sum_n phi(L u - n) S'_n gives S(u) at any u to the kernel's tolerance.
  std::vector<Complex> deconvolved;
  int deconvolved_width = 0;  // the kernel's width (0: none)
  // +1: the samples were real, -1: imaginary (the affinity i * rho), 0: general complex.
  // Real samples give S(-w) = conj S(w), imaginary ones S(-w) = -conj S(w) (the torque
  // samples q * rho share rho's), which lets queries fold conjugate pairs of modes.
  int sample_parity = 0;
};

struct NearField;  // engine/query/near_field.h

struct PairSpectra {
  std::array<std::size_t, 3> dims{};                 // common FFT grid
  double spacing = 0;                                // h, scene units
  Eigen::Vector3d length = Eigen::Vector3d::Zero();  // L_a = dims_a * h
  PartSpectrum part1, part2;
  double seconds = 0;
  // The near part of the split sum (QueryVariant::near_far), when the pair was made with
  // one (pipeline/assembly_pair.h PairOptions::near_field); not cached with the spectra.
  std::shared_ptr<const NearField> near;
  // Frequency of FFT index k along axis a (negative for k > dims/2): w = k' / L_a.
  double frequency(int axis, std::size_t k) const;
  // +1 when the terms of the correlation sum at w and -w are complex conjugates (both
  // parts' samples real, or both imaginary, so the correlation is real); else 0.
  int conjugate_pairs() const { return part1.sample_parity * part2.sample_parity == 1 ? 1 : 0; }
  // The kernel that evaluates part2.deconvolved (its width; beta as es_kernel_for).
  EsKernel rotation_kernel() const;
};

// Signed index k' of FFT index k on an axis of n points: k, or k - n above n / 2.
inline int signed_index(std::size_t k, std::size_t n) { return k <= n / 2 ? int(k) : int(k) - int(n); }

// Forward FFTs of the affinity fields i * rho (engine/fields/descriptors.h affinity_imaginary),
// and part 2's deconvolved spectrum when options ask for it. Both fields must share a spacing.
// Throws snapfit::Error for mismatched spacings or an FFT failure (naming the device).
PairSpectra compute_pair_spectra(const FftLibrary& library, const ComputeContext& ctx, const DescriptorFields& part1,
                                 const DescriptorFields& part2, const SpectrumOptions& options = {});

// Same, from arbitrary complex sample grids (tests with analytic fields use this):
// values[i] = rho(grid.point(i)), x fastest.
PairSpectra compute_pair_spectra(const FftLibrary& library, const ComputeContext& ctx, const GridSpec& grid1,
                                 const std::vector<Complex>& rho1, const GridSpec& grid2,
                                 const std::vector<Complex>& rho2, const SpectrumOptions& options = {});

}  // namespace snapfit
