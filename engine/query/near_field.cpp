#include "engine/query/near_field.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

#include "engine/spectra/box_fft.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// G(w) per axis: G is separable, exp(-2 pi^2 a^2 (w_x^2 + w_y^2 + w_z^2)).
std::array<std::vector<double>, 3> gaussian_factors(const PairSpectra& s, double a) {
  std::array<std::vector<double>, 3> g;
  for (int ax = 0; ax < 3; ++ax)
    for (std::size_t k = 0; k < s.dims[ax]; ++k) {
      const double w = s.frequency(ax, k);
      g[ax].push_back(std::exp(-2 * kPi * kPi * a * a * w * w));
    }
  return g;
}

// The fine nodes kept along each axis: indices first .. first + count - 1 (node n at
// c1 + n h / 2, c1 part 1's centre), the whole period 2 N_ax when that is as many.
struct KeptNodes {
  std::array<int, 3> first{}, count{};
  std::size_t bytes() const { return sizeof(Eigen::Vector4f) * std::size_t(count[0]) * count[1] * count[2]; }
};

// Nodes covering [low, high] (scene units from c1) per axis and the kernel's reach.
KeptNodes nodes_covering(const PairSpectra& s, const Eigen::Vector3d& low, const Eigen::Vector3d& high,
                         double fine_spacing, int kernel_width) {
  KeptNodes k;
  for (int ax = 0; ax < 3; ++ax) {
    const int period = 2 * static_cast<int>(s.dims[ax]);
    const int first = static_cast<int>(std::floor(low[ax] / fine_spacing)) - kernel_width;
    const int last = static_cast<int>(std::ceil(high[ax] / fine_spacing)) + kernel_width;
    if (last - first + 1 >= period) {
      k.first[ax] = -period / 2, k.count[ax] = period;
    } else {
      k.first[ax] = first, k.count[ax] = std::max(0, last - first + 1);
    }
  }
  return k;
}

// The nodes kept. Without a reach: part 1's samples and margin_widths a beyond them. With
// one: where part 2's samples can be, as far beyond part 1's samples as max_bytes allows
// (margins of margin_widths a and up, by halves), since r1 falls off away from them.
KeptNodes kept_nodes(const PairSpectra& s, const NearFieldOptions& o, double width, double fine_spacing,
                     int kernel_width) {
  const Eigen::Vector3d& half = s.part1.half_extent;
  const auto around_part1 = [&](double widths) {
    return Eigen::AlignedBox3d(-half.array() - widths * width, half.array() + widths * width);
  };
  if (!o.reach) {
    const Eigen::AlignedBox3d b = around_part1(o.margin_widths);
    return nodes_covering(s, b.min(), b.max(), fine_spacing, kernel_width);
  }
  const Eigen::AlignedBox3d reach(o.reach->min() - s.part1.centre, o.reach->max() - s.part1.centre);
  const KeptNodes all = nodes_covering(s, reach.min(), reach.max(), fine_spacing, kernel_width);
  KeptNodes kept;
  for (double widths = std::max(o.margin_widths, 1.0);; widths *= 1.5) {
    const Eigen::AlignedBox3d b = reach.intersection(around_part1(widths));
    if (b.isEmpty()) continue;  // part 2 stays farther from part 1's samples
    const KeptNodes k = nodes_covering(s, b.min(), b.max(), fine_spacing, kernel_width);
    if (kept.bytes() > 0 && k.bytes() > o.max_bytes) break;
    kept = k;
    if (k.first == all.first && k.count == all.count) break;
  }
  if (kept.bytes() == 0) {
    const Eigen::AlignedBox3d b = around_part1(o.margin_widths);
    return nodes_covering(s, b.min(), b.max(), fine_spacing, kernel_width);
  }
  return kept;
}

// NearField::edge_value and edge_gradient: the root mean square of |r1| and |grad r1| over
// the kept nodes' outer shell (a kernel's width deep, on the faces that do not wrap).
void set_edge_bounds(NearField& near) {
  if (near.periodic) return;
  const int w = near.kernel.width;
  double value = 0, gradient = 0;
  std::size_t count = 0;
  const auto on_shell = [&](int i, int ax) { return !near.wraps[ax] && (i < w || i >= near.dims[ax] - w); };
  for (int k = 0; k < near.dims[2]; ++k)
    for (int j = 0; j < near.dims[1]; ++j)
      for (int i = 0; i < near.dims[0]; ++i) {
        if (!on_shell(i, 0) && !on_shell(j, 1) && !on_shell(k, 2)) continue;
        const Eigen::Vector4f& n = near.node[near.index(i, j, k)];
        value += double(n[0]) * n[0];
        gradient += double(n.tail<3>().squaredNorm());
        ++count;
      }
  if (count > 0) {
    near.edge_value = std::sqrt(value / double(count));
    near.edge_gradient = std::sqrt(gradient / double(count));
  }
}

}  // namespace

NearField build_near_field(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                           const GridSpec& grid2, const std::vector<Complex>& rho2, const NearFieldOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (!(options.width_spacings > 0)) throw Error("near field: the Gaussian's width must be positive");
  if (!(options.margin_widths >= 0)) throw Error("near field: the margin must not be negative");
  if (options.kernel_width < 2 || options.kernel_width > 16) throw Error("near field: the kernel width must be 2-16");
  const int parity = spectra.part1.sample_parity;
  if (parity == 0 || parity != spectra.part2.sample_parity)
    throw Error("near field: both parts' samples must be real or both imaginary (the affinity i * rho is)");
  if (rho2.size() != grid2.count()) throw Error("near field: part 2's samples do not match its grid");

  NearField near;
  near.width = options.width_spacings * spectra.spacing;
  near.kernel = es_kernel_for(std::pow(10.0, -(options.kernel_width - 1)));
  near.fine_spacing = 0.5 * spectra.spacing;
  const std::array<std::vector<double>, 3> g = gaussian_factors(spectra, near.width);

  // The far part's spectrum.
  const auto& d = spectra.dims;
  near.far_rho1 = spectra.part1.rho;
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      for (std::size_t x = 0; x < d[0]; ++x)
        near.far_rho1[x + d[0] * (y + d[1] * z)] *= static_cast<float>(g[0][x] * g[1][y] * g[2][z]);

  // The fine box (twice the FFT box per axis, node n at c1 + n h / 2, periodic) and the
  // nodes kept (kept_nodes).
  const std::array<std::size_t, 3> m{2 * d[0], 2 * d[1], 2 * d[2]};
  const KeptNodes kept = kept_nodes(spectra, options, near.width, near.fine_spacing, near.kernel.width);
  const std::array<int, 3>& lo = kept.first;
  near.dims = kept.count;
  for (int ax = 0; ax < 3; ++ax) near.wraps[ax] = near.dims[ax] == int(m[ax]);
  near.periodic = near.wraps[0] && near.wraps[1] && near.wraps[2];
  near.origin = spectra.part1.centre + near.fine_spacing * Eigen::Vector3d(lo[0], lo[1], lo[2]);

  // Series coefficients: B_k = S1 (1 - G) dw / Phi per axis (Phi at k / (2 N): the fine
  // box's node units), the gradient's times 2 pi i w_a; the fine box's inverse DFT gives the
  // deconvolved nodes. Fine node n = 2 p + s (s in {0, 1}^3) is the coarse box's inverse
  // FFT of B_k e^{pi i k.s / N} at p, so eight transforms of the spectra's own size give
  // them (no plan twice as large per axis).
  std::array<std::vector<double>, 3> inverse_phi;
  for (int ax = 0; ax < 3; ++ax)
    for (std::size_t k = 0; k < d[ax]; ++k)
      inverse_phi[ax].push_back(1.0 / near.kernel.transform(double(signed_index(k, d[ax])) / double(m[ax])));
  const double dw = 1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z());
  const std::size_t count = d[0] * d[1] * d[2];
  std::vector<std::complex<double>> series(count);
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      for (std::size_t x = 0; x < d[0]; ++x)
        series[x + d[0] * (y + d[1] * z)] = std::complex<double>(spectra.part1.rho[x + d[0] * (y + d[1] * z)]) *
                                            (1 - g[0][x] * g[1][y] * g[2][z]) * dw * inverse_phi[0][x] *
                                            inverse_phi[1][y] * inverse_phi[2][z];
  const BoxFft fft(library, ctx, d);
  std::vector<Complex> coarse(count);
  near.node.assign(std::size_t(near.dims[0]) * near.dims[1] * near.dims[2], Eigen::Vector4f::Zero());
  for (int c = 0; c < 4; ++c)      // value, then the gradient's components
    for (int s = 0; s < 8; ++s) {  // sub-lattice
      const int sx = s & 1, sy = (s >> 1) & 1, sz = (s >> 2) & 1;
      std::array<std::vector<std::complex<double>>, 3> shift;
      for (int ax = 0; ax < 3; ++ax)
        for (std::size_t k = 0; k < d[ax]; ++k) {
          const int on = ax == 0 ? sx : ax == 1 ? sy : sz;
          const double turn = on * kPi * signed_index(k, d[ax]) / double(d[ax]);
          std::complex<double> f(std::cos(turn), std::sin(turn));
          if (c == ax + 1) f *= std::complex<double>(0, 2 * kPi * spectra.frequency(ax, k));
          shift[ax].push_back(f);
        }
      for (std::size_t z = 0; z < d[2]; ++z)
        for (std::size_t y = 0; y < d[1]; ++y) {
          const std::complex<double> yz = shift[1][y] * shift[2][z];
          for (std::size_t x = 0; x < d[0]; ++x) {
            const std::size_t i = x + d[0] * (y + d[1] * z);
            coarse[i] = Complex(series[i] * shift[0][x] * yz);
          }
        }
      fft.transform(FftDirection::inverse, coarse);
      // Kept fine node (i, j, k) is fine index lo + (i, j, k) (periodic in m), on this
      // sub-lattice when its parity matches s.
      for (int k = 0; k < near.dims[2]; ++k) {
        const long fz = ((lo[2] + k) % long(m[2]) + long(m[2])) % long(m[2]);
        if ((fz & 1) != sz) continue;
        for (int j = 0; j < near.dims[1]; ++j) {
          const long fy = ((lo[1] + j) % long(m[1]) + long(m[1])) % long(m[1]);
          if ((fy & 1) != sy) continue;
          for (int i = 0; i < near.dims[0]; ++i) {
            const long fx = ((lo[0] + i) % long(m[0]) + long(m[0])) % long(m[0]);
            if ((fx & 1) != sx) continue;
            const Complex v = coarse[std::size_t(fx / 2) + d[0] * (std::size_t(fy / 2) + d[1] * std::size_t(fz / 2))];
            // The residual of an imaginary field is i r1: keep r1.
            near.node[near.index(i, j, k)][c] = parity < 0 ? v.imag() : v.real();
          }
        }
      }
    }

  set_edge_bounds(near);

  // E_near = -Re h^3 sum_j rho2_j r1: for imaginary samples (i v2)(i r1) = -v2 r1, for real ones v2 r1.
  const double h3 = grid2.spacing * grid2.spacing * grid2.spacing;
  for (std::size_t j = 0; j < rho2.size(); ++j) {
    const double v = parity < 0 ? rho2[j].imag() : -rho2[j].real();
    if (v == 0) continue;
    const Eigen::Vector3d x = grid2.point(j);
    near.samples.emplace_back(float(x.x()), float(x.y()), float(x.z()), float(h3 * v));
  }
  near.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return near;
}

NearWrench near_wrench(const NearField& near, const Pose& pose) {
  const Eigen::Matrix3f R = pose.rotation.normalized().toRotationMatrix().cast<float>();
  const Eigen::Vector3f t = ((pose.translation - near.origin) / near.fine_spacing).cast<float>();
  const float scale = float(1 / near.fine_spacing);
  const int w = near.kernel.width;
  const float half = 0.5f * float(w);
  NearWrench out;
  double e = 0;
  Eigen::Vector3d f = Eigen::Vector3d::Zero(), tq = Eigen::Vector3d::Zero();
  double left_weight = 0, left_moment = 0;  // sum |q_j| and |q_j| |lever_j| with taps off the kept nodes
  for (const Eigen::Vector4f& s : near.samples) {
    const Eigen::Vector3f lever = R * s.head<3>();
    const Eigen::Vector3f u = lever * scale + t;  // fine-node units from near.origin
    int first[3];
    float wv[3][16];
    bool inside = true, touches = true, beyond = false;  // beyond: a tap off the kept nodes
    for (int ax = 0; ax < 3; ++ax) {
      first[ax] = static_cast<int>(std::ceil(u[ax] - half));
      const bool in = first[ax] >= 0 && first[ax] + w <= near.dims[ax];
      inside = inside && in;
      if (near.wraps[ax]) continue;
      beyond = beyond || !in;
      touches = touches && first[ax] + w > 0 && first[ax] < near.dims[ax];
    }
    // A sample with taps off the kept nodes: its weight times the share of its kernel's
    // weight they carry.
    const auto leave_out = [&](double share) {
      const double q = std::abs(double(s[3])) * share;
      left_weight += q;
      left_moment += q * double(lever.norm());
    };
    if (!touches) {
      if (beyond) leave_out(1);
      continue;
    }
    for (int ax = 0; ax < 3; ++ax)
      for (int q = 0; q < w; ++q) wv[ax][q] = float(near.kernel.value(double(u[ax]) - (first[ax] + q)));
    Eigen::Vector4f acc = Eigen::Vector4f::Zero();
    if (inside) {
      for (int qz = 0; qz < w; ++qz)
        for (int qy = 0; qy < w; ++qy) {
          const Eigen::Vector4f* row = &near.node[near.index(first[0], first[1] + qy, first[2] + qz)];
          Eigen::Vector4f line = wv[0][0] * row[0];
          for (int qx = 1; qx < w; ++qx) line += wv[0][qx] * row[qx];
          acc += (wv[1][qy] * wv[2][qz]) * line;
        }
    } else {
      // Taps off the kept nodes: wrapped along an axis where the fine box is kept whole,
      // else left out, the nodes beyond taken as zero, so that the energy stays continuous
      // (to the kernel's edge value) as a sample's taps leave the kept region.
      double kept = 0;  // sum |tap| over the kept nodes
      auto at = [&](int i, int ax) {
        if (near.wraps[ax]) return ((i % near.dims[ax]) + near.dims[ax]) % near.dims[ax];
        return i >= 0 && i < near.dims[ax] ? i : -1;
      };
      for (int qz = 0; qz < w; ++qz)
        for (int qy = 0; qy < w; ++qy)
          for (int qx = 0; qx < w; ++qx) {
            const int i = at(first[0] + qx, 0), j = at(first[1] + qy, 1), k = at(first[2] + qz, 2);
            if (i < 0 || j < 0 || k < 0) continue;
            const float tap = wv[0][qx] * wv[1][qy] * wv[2][qz];
            acc += tap * near.node[near.index(i, j, k)];
            kept += std::abs(tap);
          }
      if (beyond) {
        double all = 1;
        for (int ax = 0; ax < 3; ++ax) {
          double sum = 0;
          for (int q = 0; q < w; ++q) sum += std::abs(wv[ax][q]);
          all *= sum;
        }
        leave_out(std::max(0.0, 1 - kept / all));
      }
    }
    ++out.samples;
    const double q = s[3];
    const Eigen::Vector3d force = -q * acc.tail<3>().cast<double>();
    e += q * acc[0];
    f += force;
    tq += lever.cast<double>().cross(force);
  }
  out.energy = e;
  out.force = f;
  out.torque = tq;
  out.left_out.energy = left_weight * near.edge_value;
  out.left_out.force = left_weight * near.edge_gradient;
  out.left_out.torque = left_moment * near.edge_gradient;
  return out;
}

PairSpectra far_spectra(const PairSpectra& spectra, const NearField& near) {
  PairSpectra far = spectra;
  far.part1.rho = near.far_rho1;
  return far;
}

}  // namespace snapfit
