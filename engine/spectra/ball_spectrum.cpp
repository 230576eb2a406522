#include "engine/spectra/ball_spectrum.h"

#include <algorithm>
#include <cmath>

#include "engine/spectra/es_kernel.h"
#include "engine/runtime/kernel_sources.h"
#include "engine/spectra/spectra.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d mode_frequency(const std::array<int, 3>& k, const FrequencyLattice& lattice) {
  return Eigen::Vector3d(k[0] / lattice.length.x(), k[1] / lattice.length.y(), k[2] / lattice.length.z());
}

// Barycentric interpolation at the P Chebyshev points of [lo, hi]: the nodes, and the
// Lagrange weights l_p(r) of a radius.
struct ChebyshevNodes {
  std::vector<double> nodes, barycentric;
  ChebyshevNodes(int count, double lo, double hi) {
    for (int p = 0; p < count; ++p) {
      const double angle = kPi * (2 * p + 1) / (2.0 * count);
      nodes.push_back(0.5 * (lo + hi) + 0.5 * (hi - lo) * std::cos(angle));
      barycentric.push_back((p % 2 == 0 ? 1.0 : -1.0) * std::sin(angle));
    }
  }
  std::vector<double> weights(double r) const {
    std::vector<double> l(nodes.size(), 0.0);
    double total = 0;
    for (std::size_t p = 0; p < nodes.size(); ++p) {
      if (r == nodes[p]) {
        std::fill(l.begin(), l.end(), 0.0);
        l[p] = 1;
        return l;
      }
      l[p] = barycentric[p] / (r - nodes[p]);
      total += l[p];
    }
    for (double& v : l) v /= total;
    return l;
  }
};

// The fewest Chebyshev nodes (up to 64) that interpolate r -> Bhat(r, q) on [lo, hi] to
// tolerance * Bhat(r, 0) for every q up to q_max (checked on a fine sample of both).
int radius_nodes_for(double lo, double hi, double q_max, double tolerance) {
  if (hi - lo <= 1e-12 * hi) return 1;
  for (int count = 2; count <= 64; ++count) {
    const ChebyshevNodes cheb(count, lo, hi);
    double worst = 0;
    for (int i = 0; i <= 96 && worst <= tolerance; ++i) {
      const double r = lo + (hi - lo) * i / 96.0;
      const std::vector<double> l = cheb.weights(r);
      for (int s = 0; s <= 32; ++s) {
        const double q = q_max * s / 32.0;
        double interpolated = 0;
        for (int p = 0; p < count; ++p)
          interpolated += l[std::size_t(p)] * ball_transform(cheb.nodes[std::size_t(p)], q);
        worst = std::max(worst, std::abs(interpolated - ball_transform(r, q)) / ball_transform(r, 0));
      }
    }
    if (worst <= tolerance) return count;
  }
  throw Error("ball spectrum: radii from " + std::to_string(lo) + " to " + std::to_string(hi) +
              " need more than 64 interpolation nodes at this lattice; split the ball set");
}

}  // namespace

double ball_transform(double radius, double q) {
  const double t = 2 * kPi * std::abs(q) * radius, volume = 4.0 / 3.0 * kPi * radius * radius * radius;
  if (t < 1e-2) {
    const double t2 = t * t;
    return volume * (1 - t2 / 10 + t2 * t2 / 280);
  }
  return volume * 3 * (std::sin(t) - t * std::cos(t)) / (t * t * t);
}

std::vector<std::array<int, 3>> lattice_modes(const FrequencyLattice& lattice) {
  std::vector<std::array<int, 3>> modes;
  modes.reserve(lattice.count());
  const auto& d = lattice.dims;
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      for (std::size_t x = 0; x < d[0]; ++x)
        modes.push_back({signed_index(x, d[0]), signed_index(y, d[1]), signed_index(z, d[2])});
  return modes;
}

std::vector<std::complex<double>> ball_spectrum_reference(const std::vector<Ball>& balls,
                                                          const FrequencyLattice& lattice,
                                                          const std::vector<std::array<int, 3>>& modes) {
  std::vector<std::complex<double>> out(modes.size());
  for (std::size_t m = 0; m < modes.size(); ++m) {
    const Eigen::Vector3d w = mode_frequency(modes[m], lattice);
    std::complex<double> sum = 0;
    for (const Ball& b : balls)
      sum += ball_transform(b.radius, w.norm()) * std::polar(1.0, -2 * kPi * w.dot(b.centre - lattice.centre));
    out[m] = sum;
  }
  return out;
}

std::vector<std::complex<float>> ball_spectrum_direct(const ComputeContext& ctx, const std::vector<Ball>& balls,
                                                      const FrequencyLattice& lattice,
                                                      const std::vector<std::array<int, 3>>& modes,
                                                      const ProgramCacheConfig& cache) {
  const std::vector<std::array<int, 3>> all = modes.empty() ? lattice_modes(lattice) : modes;
  std::vector<std::complex<float>> out(all.size());
  if (all.empty() || balls.empty()) return out;
  std::vector<cl_int4> k(all.size());
  for (std::size_t m = 0; m < all.size(); ++m) k[m] = cl_int4{{all[m][0], all[m][1], all[m][2], 0}};
  std::vector<cl_float4> b(balls.size());
  for (std::size_t j = 0; j < balls.size(); ++j) {
    const Eigen::Vector3d y = balls[j].centre - lattice.centre;
    b[j] = cl_float4{{float(y.x()), float(y.y()), float(y.z()), float(balls[j].radius)}};
  }
  try {
    cl::Kernel kernel(build_program(ctx, "ball_ndft", kernel_source("ball_ndft"), "-cl-std=CL1.2", cache).program,
                      "ball_ndft");
    cl::Buffer modes_buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_int4) * k.size(), k.data());
    cl::Buffer balls_buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * b.size(),
                            b.data());
    cl::Buffer result(ctx.context, CL_MEM_WRITE_ONLY, sizeof(cl_float2) * all.size());
    kernel.setArg(0, modes_buffer);
    kernel.setArg(1, static_cast<cl_int>(all.size()));
    kernel.setArg(2, balls_buffer);
    kernel.setArg(3, static_cast<cl_int>(b.size()));
    kernel.setArg(4, cl_float4{{float(1.0 / lattice.length.x()), float(1.0 / lattice.length.y()),
                                float(1.0 / lattice.length.z()), 0.0f}});
    kernel.setArg(5, result);
    const std::size_t group = 64;
    ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange((all.size() + group - 1) / group * group),
                                   cl::NullRange);
    ctx.queue.enqueueReadBuffer(result, CL_TRUE, 0, sizeof(cl_float2) * all.size(), out.data());
  } catch (const cl::Error& e) {
    throw Error("ball spectrum on " + ctx.device.info.name + ": " + e.what() + " (" + std::to_string(e.err()) + ")");
  }
  return out;
}

std::vector<std::complex<float>> ball_spectrum_nufft(const FftLibrary& library, const ComputeContext& ctx,
                                                     const std::vector<Ball>& balls, const FrequencyLattice& lattice,
                                                     const BallNufftOptions& options, BallNufftStats* stats) {
  if (balls.empty()) throw Error("ball spectrum: no balls");
  if (!(options.tolerance > 0 && options.tolerance <= 0.1))
    throw Error("ball spectrum: tolerance must be in (0, 0.1] (got " + std::to_string(options.tolerance) + ")");
  if (!(options.oversampling >= 2.0)) throw Error("ball spectrum: oversampling must be at least 2");
  const EsKernel kernel = es_kernel_for(options.tolerance);
  std::array<std::size_t, 3> fine{};
  double q_max2 = 0;
  for (int a = 0; a < 3; ++a) {
    fine[std::size_t(a)] = next_fft_size(
        std::max<std::size_t>(std::size_t(2 * kernel.width),
                              std::size_t(std::ceil(options.oversampling * double(lattice.dims[std::size_t(a)])))));
    q_max2 += std::pow(double(lattice.dims[std::size_t(a)] / 2) / lattice.length[a], 2);
  }
  double lo = balls[0].radius, hi = balls[0].radius;
  for (const Ball& b : balls) {
    if (!(b.radius > 0) || !b.centre.allFinite())
      throw Error("ball spectrum: a ball has a non-positive radius or a non-finite centre");
    lo = std::min(lo, b.radius);
    hi = std::max(hi, b.radius);
  }
  const ChebyshevNodes cheb(radius_nodes_for(lo, hi, std::sqrt(q_max2), 0.25 * options.tolerance), lo, hi);
  const int taps = kernel.width;
  // Per ball and axis: the first fine node of its taps (periodic) and the taps' weights.
  const std::size_t n = balls.size();
  std::vector<std::array<long, 3>> first(n);
  std::vector<double> tap(n * 3 * std::size_t(taps));
  for (std::size_t j = 0; j < n; ++j)
    for (int a = 0; a < 3; ++a) {
      const double x = (balls[j].centre[a] - lattice.centre[a]) / lattice.length[a];  // periods
      const double t = (x - std::floor(x)) * double(fine[std::size_t(a)]);            // fine nodes, in [0, n)
      const long i0 = long(std::ceil(t - 0.5 * taps));
      first[j][std::size_t(a)] = i0;
      for (int s = 0; s < taps; ++s)
        tap[(j * 3 + std::size_t(a)) * std::size_t(taps) + std::size_t(s)] = kernel.value(double(i0 + s) - t);
    }
  // 1 / Phi(k' / n) per axis for the lattice's modes.
  std::array<std::vector<double>, 3> deconvolve;
  for (std::size_t a = 0; a < 3; ++a) {
    deconvolve[a].resize(lattice.dims[a]);
    for (std::size_t k = 0; k < lattice.dims[a]; ++k)
      deconvolve[a][k] = 1.0 / kernel.transform(double(signed_index(k, lattice.dims[a])) / double(fine[a]));
  }
  const std::vector<std::array<int, 3>> modes = lattice_modes(lattice);
  std::vector<std::complex<double>> sum(modes.size(), 0.0);
  std::vector<std::complex<float>> grid(fine[0] * fine[1] * fine[2]);
  try {
    const Fft3d fft(library, ctx, fine);
    cl::Buffer in(ctx.context, CL_MEM_READ_WRITE, sizeof(std::complex<float>) * grid.size());
    cl::Buffer out(ctx.context, CL_MEM_READ_WRITE, sizeof(std::complex<float>) * grid.size());
    for (std::size_t p = 0; p < cheb.nodes.size(); ++p) {
      std::vector<double> spread(grid.size(), 0.0);
      for (std::size_t j = 0; j < n; ++j) {
        const double c = cheb.weights(balls[j].radius)[p];
        const double* tx = &tap[(j * 3 + 0) * std::size_t(taps)];
        const double* ty = &tap[(j * 3 + 1) * std::size_t(taps)];
        const double* tz = &tap[(j * 3 + 2) * std::size_t(taps)];
        for (int sz = 0; sz < taps; ++sz) {
          const long iz = ((first[j][2] + sz) % long(fine[2]) + long(fine[2])) % long(fine[2]);
          for (int sy = 0; sy < taps; ++sy) {
            const long iy = ((first[j][1] + sy) % long(fine[1]) + long(fine[1])) % long(fine[1]);
            const double wyz = c * tz[sz] * ty[sy];
            double* row = &spread[fine[0] * (std::size_t(iy) + fine[1] * std::size_t(iz))];
            for (int sx = 0; sx < taps; ++sx)
              row[((first[j][0] + sx) % long(fine[0]) + long(fine[0])) % long(fine[0])] += wyz * tx[sx];
          }
        }
      }
      for (std::size_t i = 0; i < grid.size(); ++i) grid[i] = std::complex<float>(float(spread[i]), 0.0f);
      ctx.queue.enqueueWriteBuffer(in, CL_TRUE, 0, sizeof(std::complex<float>) * grid.size(), grid.data());
      fft.transform(FftDirection::forward, in, out);
      ctx.queue.enqueueReadBuffer(out, CL_TRUE, 0, sizeof(std::complex<float>) * grid.size(), grid.data());
      for (std::size_t m = 0; m < modes.size(); ++m) {
        const auto& k = modes[m];
        const std::size_t x = std::size_t((k[0] + long(fine[0])) % long(fine[0]));
        const std::size_t y = std::size_t((k[1] + long(fine[1])) % long(fine[1]));
        const std::size_t z = std::size_t((k[2] + long(fine[2])) % long(fine[2]));
        const std::size_t lx = m % lattice.dims[0], ly = m / lattice.dims[0] % lattice.dims[1],
                          lz = m / (lattice.dims[0] * lattice.dims[1]);
        const double scale = deconvolve[0][lx] * deconvolve[1][ly] * deconvolve[2][lz] *
                             ball_transform(cheb.nodes[p], mode_frequency(k, lattice).norm());
        sum[m] += scale * std::complex<double>(grid[x + fine[0] * (y + fine[1] * z)]);
      }
    }
  } catch (const cl::Error& e) {
    throw Error("ball spectrum on " + ctx.device.info.name + ": " + e.what() + " (" + std::to_string(e.err()) + ")");
  }
  if (stats) {
    stats->radius_nodes = int(cheb.nodes.size());
    stats->kernel_width = kernel.width;
    stats->fine_dims = fine;
  }
  std::vector<std::complex<float>> result(sum.size());
  for (std::size_t m = 0; m < sum.size(); ++m) result[m] = std::complex<float>(sum[m]);
  return result;
}

}  // namespace snapfit
