#include "engine/spectra/es_kernel.h"

#include <algorithm>
#include <array>

namespace snapfit {
namespace {

// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre recurrence).
struct GaussLegendre {
  static constexpr int kPoints = 64;
  std::array<double, kPoints> x{}, w{};
  GaussLegendre() {
    const double pi = 3.14159265358979323846;
    for (int i = 0; i < kPoints; ++i) {
      double z = std::cos(pi * (i + 0.75) / (kPoints + 0.5)), dp = 0;
      for (int it = 0; it < 100; ++it) {
        double p0 = 1, p1 = z;
        for (int n = 2; n <= kPoints; ++n) {
          const double p2 = ((2 * n - 1) * z * p1 - (n - 1) * p0) / n;
          p0 = p1;
          p1 = p2;
        }
        dp = kPoints * (z * p1 - p0) / (z * z - 1);
        const double step = p1 / dp;
        z -= step;
        if (std::abs(step) < 1e-16) break;
      }
      x[i] = z;
      w[i] = 2 / ((1 - z * z) * dp * dp);
    }
  }
};

const GaussLegendre& gauss_legendre() {
  static const GaussLegendre rule;
  return rule;
}

}  // namespace

double EsKernel::value(double s) const {
  const double t = 2 * s / width;
  if (!(std::abs(t) < 1)) return 0;
  return std::exp(beta * (std::sqrt(1 - t * t) - 1));
}

double EsKernel::derivative(double s) const {
  const double t = 2 * s / width;
  if (!(std::abs(t) < 1)) return 0;
  const double root = std::sqrt(1 - t * t);
  return value(s) * beta * (-t / root) * (2.0 / width);
}

double EsKernel::transform(double xi) const {
  // phi is even: Phi(xi) = 2 integral_0^{w/2} phi(s) cos(2 pi s xi) ds, in two halves so
  // the square-root end at s = w/2 is resolved.
  const GaussLegendre& g = gauss_legendre();
  const double half = 0.5 * width, pi2 = 6.283185307179586476925;
  double sum = 0;
  for (const auto& [a, b] : {std::pair{0.0, 0.8 * half}, std::pair{0.8 * half, half}}) {
    const double mid = 0.5 * (a + b), rad = 0.5 * (b - a);
    for (int i = 0; i < GaussLegendre::kPoints; ++i) {
      const double s = mid + rad * g.x[i];
      sum += g.w[i] * rad * value(s) * std::cos(pi2 * s * xi);
    }
  }
  return 2 * sum;
}

EsKernel es_kernel_for(double tolerance) {
  EsKernel k;
  k.width = std::max(2, static_cast<int>(std::ceil(std::log10(1.0 / tolerance))) + 1);
  k.beta = 2.30 * k.width;
  return k;
}

}  // namespace snapfit
