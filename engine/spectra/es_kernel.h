#pragma once
// The "exponential of semicircle" kernel of non-uniform FFTs (Barnett et al., FINUFFT),
// used to evaluate a sampled spectrum exactly (to a tolerance) at any frequency, in
// particular at part 2's rotated frequencies w' = -R^T w:
//
//   phi(s) = exp(beta (sqrt(1 - (2 s / width)^2) - 1)),  |s| <= width / 2 (s in nodes),
//
// with beta = 2.30 width (FINUFFT's choice for 2x oversampling). Type 2 (uniform samples
// to a non-uniform frequency u): with part 2's samples c_j at x_j (|x_j| <= L / (2 sigma),
// sigma >= 2 the oversampling of the FFT box L) pre-divided by Phi(x_j / L) per axis,
// Phi the kernel's Fourier transform, their DFT S'_k on the lattice k / L gives
//
//   S(u) = sum_j c_j exp(-2 pi i u.x_j) = sum_k phi(L u - k) S'_k  (to the tolerance),
//
// a sum of width^3 taps around L u. The error falls about tenfold per unit of width:
// width 7 gives ~1e-6 of sum |c_j| at sigma = 2, less at larger sigma.
#include <cmath>

namespace snapfit {

struct EsKernel {
  int width = 7;
  double beta = 2.30 * 7;

  // phi(s) and phi'(s) (s in nodes); 0 outside |s| <= width / 2.
  double value(double s) const;
  double derivative(double s) const;
  // Phi(xi) = integral of phi(s) cos(2 pi s xi) ds (xi in cycles per node), by
  // Gauss-Legendre quadrature in double.
  double transform(double xi) const;
};

// The kernel for a tolerance: width = ceil(log10(1 / tolerance)) + 1, at least 2.
EsKernel es_kernel_for(double tolerance);

}  // namespace snapfit
