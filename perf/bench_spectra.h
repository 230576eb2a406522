#pragma once
// Spectra of two synthetic parts for the full-map benchmarks (bench_fft, bench_search).
#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "engine/spectra/spectra.h"
#include "snapfit/error.h"

namespace snapfit::bench {

// Spectra on an FFT grid of exactly `d` points (oversampling 1, the fields filling the
// central half of the box): part 1 a ball, part 2 a box, values i * indicator as for the
// indicator descriptor.
inline PairSpectra synthetic_spectra(const FftLibrary& lib, const ComputeContext& ctx,
                                     const std::array<std::size_t, 3>& d, double spacing) {
  GridSpec g;
  g.spacing = spacing;
  g.dims = Eigen::Vector3i(int(d[0]), int(d[1]), int(d[2]));
  g.origin = -0.5 * spacing * Eigen::Vector3d(double(d[0]), double(d[1]), double(d[2]));
  const Eigen::Vector3d half = 0.5 * spacing * Eigen::Vector3d(double(d[0]), double(d[1]), double(d[2]));
  std::vector<Complex> rho1(g.count()), rho2(g.count());
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        const Eigen::Vector3d q = p.cwiseQuotient(half);  // in [-1, 1)
        rho1[g.index(i, j, k)] = Complex(0.0f, q.norm() < 0.45 ? 1.0f : 0.0f);
        rho2[g.index(i, j, k)] =
            Complex(0.0f, (q.cwiseAbs().array() < Eigen::Array3d(0.3, 0.2, 0.4)).all() ? 1.0f : 0.0f);
      }
  SpectrumOptions opt;
  opt.oversampling = 1.0;
  PairSpectra s = compute_pair_spectra(lib, ctx, g, rho1, g, rho2, opt);
  if (s.dims != d)
    throw Error("synthetic spectra: got " + std::to_string(s.dims[0]) + " x " + std::to_string(s.dims[1]) + " x " +
                std::to_string(s.dims[2]) + ", wanted " + std::to_string(d[0]) + " x " + std::to_string(d[1]) + " x " +
                std::to_string(d[2]));
  return s;
}

}  // namespace snapfit::bench
