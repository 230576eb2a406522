#include "engine/spectra/spectra.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "snapfit/error.h"

namespace snapfit {
namespace {

// Where a part's samples sit in the padded box: centred, so the box centre c is the
// samples' centre (to within half a spacing) and S(w) varies slowly.
struct Placement {
  std::array<std::size_t, 3> offset;  // FFT index of sample (0, 0, 0)
  Eigen::Vector3d centre;             // c = FFT-box origin + h N / 2
};

Placement place(const GridSpec& grid, const std::array<std::size_t, 3>& dims) {
  Placement p;
  for (int a = 0; a < 3; ++a) p.offset[a] = (dims[a] - static_cast<std::size_t>(grid.dims[a])) / 2;
  const Eigen::Vector3d box_origin =
      grid.origin - grid.spacing * Eigen::Vector3d(double(p.offset[0]), double(p.offset[1]), double(p.offset[2]));
  p.centre = box_origin + 0.5 * grid.spacing * Eigen::Vector3d(double(dims[0]), double(dims[1]), double(dims[2]));
  return p;
}

// S(w_k) = rho^(w_k) exp(2 pi i w_k.c) = h^3 exp(-2 pi i w_k.(o' - c)) DFT[k] with
// o' - c = -h N / 2: the factor is h^3 (-1)^(k'x + k'y + k'z) (seed 000 eq. 13).
std::vector<Complex> centred_spectrum(const BoxFft& fft, const GridSpec& grid, const Placement& placement,
                                      const std::function<Complex(std::size_t, int, int, int)>& sample) {
  const auto dims = fft.dims();
  std::vector<Complex> padded(dims[0] * dims[1] * dims[2], Complex(0, 0));
  for (int k = 0; k < grid.dims.z(); ++k)
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const std::size_t at =
            (i + placement.offset[0]) + dims[0] * ((j + placement.offset[1]) + dims[1] * (k + placement.offset[2]));
        padded[at] = sample(grid.index(i, j, k), i, j, k);
      }
  fft.transform(FftDirection::forward, padded);
  const float h3 = static_cast<float>(grid.spacing * grid.spacing * grid.spacing);
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const long parity = signed_index(x, dims[0]) + signed_index(y, dims[1]) + signed_index(z, dims[2]);
        padded[x + dims[0] * (y + dims[1] * z)] *= (parity % 2 == 0 ? h3 : -h3);
      }
  return padded;
}

}  // namespace

EsKernel PairSpectra::rotation_kernel() const {
  EsKernel kernel;
  kernel.width = part2.deconvolved_width;
  kernel.beta = 2.30 * kernel.width;
  return kernel;
}

double PairSpectra::frequency(int axis, std::size_t k) const {
  return static_cast<double>(signed_index(k, dims[axis])) / length[axis];
}

PairSpectra compute_pair_spectra(const FftLibrary& library, const ComputeContext& ctx, const GridSpec& grid1,
                                 const std::vector<Complex>& rho1, const GridSpec& grid2,
                                 const std::vector<Complex>& rho2, const SpectrumOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (std::abs(grid1.spacing - grid2.spacing) > 1e-9 * grid1.spacing)
    throw Error("the parts' grids must share one spacing to share frequencies (got " + std::to_string(grid1.spacing) +
                " and " + std::to_string(grid2.spacing) + ")");
  if (rho1.size() != grid1.count() || rho2.size() != grid2.count())
    throw Error("spectra: field sizes do not match their grids");
  if (!(options.oversampling >= 1.0)) throw Error("spectrum oversampling must be at least 1");
  PairSpectra out;
  out.spacing = grid1.spacing;
  // The exact rotation's kernel needs part 2's samples within L / 4 of its centre:
  // 2 N2 + 4 points on each axis cover the half-spacing offsets of the centring. Each
  // axis is even: the centre c = o' + h N / 2 then lies on a node of the samples' lattice,
  // so the centred spectrum is periodic in its index, S_{k+N} = S_k, and an interpolation
  // whose taps wrap across the box's edge (a rotated frequency near Nyquist) reads the
  // right values; with N odd it is anti-periodic (S_{k+N} = -S_k).
  const bool exact_rotation = options.exact_rotation_width > 0 && options.oversampling >= 2.0;
  for (int a = 0; a < 3; ++a) {
    double points = options.oversampling * std::max(grid1.dims[a], grid2.dims[a]);
    if (exact_rotation) points = std::max(points, 2.0 * grid2.dims[a] + 4.0);
    out.dims[a] = next_even_fft_size(static_cast<std::size_t>(std::ceil(points - 1e-9)));
    out.length[a] = out.dims[a] * out.spacing;
  }
  const BoxFft fft(library, ctx, out.dims, options.fft);
  const Placement p1 = place(grid1, out.dims), p2 = place(grid2, out.dims);
  out.part1.centre = p1.centre;
  out.part2.centre = p2.centre;
  // Farthest sample from the centre along each axis (the samples are not exactly centred).
  auto half_extent = [](const GridSpec& g, const Eigen::Vector3d& c) {
    const Eigen::Vector3d last = g.point(g.dims.x() - 1, g.dims.y() - 1, g.dims.z() - 1);
    return Eigen::Vector3d((g.origin - c).cwiseAbs().cwiseMax((last - c).cwiseAbs()));
  };
  out.part1.half_extent = half_extent(grid1, p1.centre);
  out.part2.half_extent = half_extent(grid2, p2.centre);
  // +1 real, -1 imaginary, 0 general (an all-zero field counts as real).
  auto parity = [](const std::vector<Complex>& v) {
    const bool real = std::all_of(v.begin(), v.end(), [](const Complex& c) { return c.imag() == 0.0f; });
    const bool imaginary = std::all_of(v.begin(), v.end(), [](const Complex& c) { return c.real() == 0.0f; });
    return real ? 1 : imaginary ? -1 : 0;
  };
  out.part1.sample_parity = parity(rho1);
  out.part2.sample_parity = parity(rho2);
  out.part1.rho = centred_spectrum(fft, grid1, p1, [&](std::size_t i, int, int, int) { return rho1[i]; });
  out.part2.rho = centred_spectrum(fft, grid2, p2, [&](std::size_t i, int, int, int) { return rho2[i]; });
  // The kernel is accurate while part 2's samples stay within L / 4 of its centre (2x
  // oversampling); a coarser box (oversampling < 2) gets no deconvolved spectrum.
  const bool deconvolve =
      exact_rotation &&
      ((2.0 * out.part2.half_extent.array() + grid2.spacing) * 2.0 <= out.length.array() * (1 + 1e-9)).all();
  if (deconvolve) {
    // c'_j = c_j / prod_a Phi((q_j - c2)_a / L_a): type-2 non-uniform FFT pre-correction
    // (engine/spectra/es_kernel.h), so the kernel's taps give S2 at any frequency.
    EsKernel kernel;
    kernel.width = options.exact_rotation_width;
    kernel.beta = 2.30 * kernel.width;
    std::array<std::vector<double>, 3> inverse;
    for (int a = 0; a < 3; ++a) {
      inverse[a].resize(static_cast<std::size_t>(grid2.dims[a]));
      for (int i = 0; i < grid2.dims[a]; ++i) {
        const double x = grid2.origin[a] + grid2.spacing * i - p2.centre[a];
        inverse[a][std::size_t(i)] = 1.0 / kernel.transform(x / out.length[a]);
      }
    }
    out.part2.deconvolved = centred_spectrum(fft, grid2, p2, [&](std::size_t i, int x, int y, int z) {
      return rho2[i] *
             static_cast<float>(inverse[0][std::size_t(x)] * inverse[1][std::size_t(y)] * inverse[2][std::size_t(z)]);
    });
    out.part2.deconvolved_width = kernel.width;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

PairSpectra compute_pair_spectra(const FftLibrary& library, const ComputeContext& ctx, const DescriptorFields& part1,
                                 const DescriptorFields& part2, const SpectrumOptions& options) {
  // The affinity is i * (lambda s) (or i * indicator): purely imaginary samples.
  auto imaginary = [](const std::vector<float>& values) {
    std::vector<Complex> out(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) out[i] = Complex(0.0f, values[i]);
    return out;
  };
  return compute_pair_spectra(library, ctx, part1.grid, imaginary(affinity_imaginary(part1)), part2.grid,
                              imaginary(affinity_imaginary(part2)), options);
}

}  // namespace snapfit
