#pragma once
// The energy split as Ewald summation splits a sum (docs/design.md "Near and far"): with
// G(w) = exp(-2 pi^2 a^2 |w|^2), a Gaussian of width a in space, the all-mode sum of
// include/snapfit/query.h is
//
//   E = sum_k G S1 S2' e^{i phi} dw  +  sum_k (1 - G) S1 S2' e^{i phi} dw  =  E_far + E_near.
//
// E_far's spectrum falls as G, so its first m' modes leave little out: it is the ordinary
// query over part 1's spectrum times G (far_spectra). E_near is summed in space, where it
// is exact at any pose: with part 2's samples rho2_j at x_j (its frame) and r1 the
// trigonometric interpolant of part 1's residual (its field less the field smoothed by G),
//
//   E_near(R, t) = -Re h^3 sum_j rho2_j r1(R x_j + t),
//
// F = -dE/dt and T = -dE/dtheta term by term (seed 000 eq. 10-12 in space). r1 is not
// sampled: it is evaluated as a type-2 non-uniform FFT evaluates a Fourier series
// (engine/spectra/es_kernel.h), from a grid twice as fine as part 1's whose values are its
// series divided by the kernel's transform, over width^3 taps; its gradient likewise from
// the series of 2 pi i w times it, so value and gradient share the taps.
//
// Only the fine nodes where part 2's samples can be are kept: the box the scene's
// trajectory or workspace lets part 2's grid sweep (pipeline/reach_region.h), as far beyond
// part 1's grid as a memory cap allows, or, when the scene does not say, part 1's grid and
// a margin of 3 a. r1 is a trigonometric interpolant: off the sample lattice it rings
// beyond part 1's grid, far more than 3 a, where part 1's field is sharp at the grid's
// scale. A sample's taps beyond the kept nodes
// add nothing (the nodes there count as zero, so the near energy stays continuous as a
// sample leaves the kept region), and what they leave out is bounded, for the error
// estimate, by the largest |r1| and |grad r1| on the kept region's outer shell times the
// samples' weights (NearWrench::left_out).
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/spectra/es_kernel.h"
#include "engine/spectra/fft3d.h"
#include "engine/spectra/spectra.h"
#include "snapfit/grid.h"
#include "snapfit/pose.h"
#include "snapfit/query.h"

namespace snapfit {

struct NearFieldOptions {
  double width_spacings = 2.0;  // a, in grid spacings
  int kernel_width = 5;         // taps per axis: about 1e-4 of the near part, its force within 0.3 % of -dE/dt
  double margin_widths = 3;     // fine nodes kept beyond part 1's samples, in widths a (no reach)
  // Where part 2's samples can be, part 1's frame (the scene's reach region): the nodes
  // kept cover it, as far beyond part 1's samples (margin_widths a and more) as max_bytes
  // of nodes allow.
  std::optional<Eigen::AlignedBox3d> reach;
  std::size_t max_bytes = std::size_t(512) << 20;
};

struct NearField {
  double width = 0;  // a, scene units
  EsKernel kernel;
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // fine node (0, 0, 0), part 1's frame
  double fine_spacing = 0;                           // h / 2
  std::array<int, 3> dims{};                         // fine nodes kept per axis
  std::array<bool, 3> wraps{};                       // the whole fine box is kept along the axis: taps wrap around
  bool periodic = false;                             // along every axis
  // The root mean square of |r1| and |grad r1| on the outer shell of the kept nodes (a
  // kernel's width deep, on the faces that do not wrap), the scale NearWrench::left_out
  // takes for the nodes beyond; 0 when periodic.
  double edge_value = 0, edge_gradient = 0;
  std::vector<Eigen::Vector4f> node;                 // r1 and its gradient (d/dx, d/dy, d/dz); x fastest
  // Part 2's nonzero samples: x_j in its frame and the weight q_j with E_near = sum_j q_j r1(y_j).
  std::vector<Eigen::Vector4f> samples;
  std::vector<Complex> far_rho1;  // S1 G: part 1's spectrum for the far part
  double seconds = 0;             // build time

  std::size_t index(int i, int j, int k) const {
    return std::size_t(i) + std::size_t(dims[0]) * (std::size_t(j) + std::size_t(dims[1]) * std::size_t(k));
  }
  std::size_t bytes() const { return node.size() * sizeof(node[0]) + samples.size() * sizeof(samples[0]); }
};

// From the pair's spectra and part 2's samples (rho2 on grid2, the samples its spectrum was
// made from). Throws snapfit::Error when the parts' samples are not both real or both
// imaginary (the near part's sum is real only then), a width is not positive, or the FFT
// fails on the device.
NearField build_near_field(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                           const GridSpec& grid2, const std::vector<Complex>& rho2, const NearFieldOptions& options);

struct NearWrench {
  double energy = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // about part 2's origin, part 1's frame
  std::size_t samples = 0;                           // part 2's samples with a tap on a kept node
  // The estimate of what the taps off the kept nodes leave out: sum over the samples with
  // such taps of |q_j| times the share of their kernel's weight there, times
  // NearField::edge_value, edge_gradient and |lever_j| edge_gradient (E, F, T).
  ErrorEstimate left_out;
};

// E_near, F_near, T_near at part 2's pose in part 1's frame. No heap allocation.
NearWrench near_wrench(const NearField& near, const Pose& pose);

// The spectra of the far part: part 1's spectrum times G, the rest shared.
PairSpectra far_spectra(const PairSpectra& spectra, const NearField& near);

}  // namespace snapfit
