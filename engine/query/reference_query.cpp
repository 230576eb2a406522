#include "engine/query/reference_query.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <numeric>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include "snapfit/error.h"

namespace snapfit {
namespace {

using Cd = std::complex<double>;

std::size_t wrap(long i, std::size_t n) { return static_cast<std::size_t>(((i % long(n)) + long(n)) % long(n)); }

// Interpolation weights along one axis at fractional index u and their derivatives;
// returns the first tap.
int axis_weights(double u, Interpolation scheme, double* w, double* dw) {
  const double f = std::floor(u), t = u - f;
  if (scheme == Interpolation::trilinear) {
    w[0] = 1 - t;
    w[1] = t;
    dw[0] = -1;
    dw[1] = 1;
    return int(f);
  }
  const double t2 = t * t, t3 = t2 * t;  // Catmull-Rom
  w[0] = 0.5 * (-t3 + 2 * t2 - t);
  w[1] = 0.5 * (3 * t3 - 5 * t2 + 2);
  w[2] = 0.5 * (-3 * t3 + 4 * t2 + t);
  w[3] = 0.5 * (t3 - t2);
  dw[0] = 0.5 * (-3 * t2 + 4 * t - 1);
  dw[1] = 0.5 * (9 * t2 - 10 * t);
  dw[2] = 0.5 * (-9 * t2 + 8 * t + 1);
  dw[3] = 0.5 * (3 * t2 - 2 * t);
  return int(f) - 1;
}

// Sums per mode: Re f, Im f, force (3), torque in part 2's frame (3).
struct Sums {
  std::array<double, 8> v{};
  Sums& operator+=(const Sums& o) {
    for (int i = 0; i < 8; ++i) v[i] += o.v[i];
    return *this;
  }
};

}  // namespace

QueryResult reference_query(const PairSpectra& s, const Pose& pose, const ReferenceOptions& options,
                            const std::vector<std::size_t>* order_in) {
  const auto start = std::chrono::steady_clock::now();
  const auto& d = s.dims;
  const std::size_t total = d[0] * d[1] * d[2];
  QueryResult r;
  r.modes = options.modes == 0 ? total : std::min(options.modes, total);

  const Eigen::Quaterniond q = pose.rotation;
  if (!pose.is_finite() || std::abs(q.norm() - 1.0) > 1e-6) {
    r.flags |= query_bad_pose;
    return r;
  }
  const Eigen::Matrix3d R = q.normalized().toRotationMatrix();
  const Eigen::Vector3d tau = pose.translation + R * s.part2.centre - s.part1.centre;
  const Eigen::Vector3d reach = s.part1.half_extent + R.cwiseAbs() * s.part2.half_extent;
  if (((tau.cwiseAbs() + reach).array() > s.length.array()).any()) {
    r.flags |= query_outside_grid;
    return r;
  }

  std::vector<std::size_t> own_order;
  const std::vector<std::size_t>& order = order_in ? *order_in : (own_order = mode_order(s));
  const double dw = 1.0 / (s.length.x() * s.length.y() * s.length.z());
  const int taps = options.interpolation == Interpolation::tricubic ? 4 : 2;
  const bool torque = options.torque;

  // S2 and its gradient (in fractional index) at fractional index u.
  const auto sample = [&](const Eigen::Vector3d& u, Cd* out) {
    double wx[4], wy[4], wz[4], dx[4], dy[4], dz[4];
    const int ix = axis_weights(u.x(), options.interpolation, wx, dx),
              iy = axis_weights(u.y(), options.interpolation, wy, dy),
              iz = axis_weights(u.z(), options.interpolation, wz, dz);
    for (int i = 0; i < 4; ++i) out[i] = 0;
    for (int c = 0; c < taps; ++c)
      for (int b = 0; b < taps; ++b)
        for (int a = 0; a < taps; ++a) {
          const std::size_t k = wrap(ix + a, d[0]) + d[0] * (wrap(iy + b, d[1]) + d[1] * wrap(iz + c, d[2]));
          const Cd v(s.part2.rho[k]);
          out[0] += wx[a] * wy[b] * wz[c] * v;
          if (torque) {
            out[1] += dx[a] * wy[b] * wz[c] * v;
            out[2] += wx[a] * dy[b] * wz[c] * v;
            out[3] += wx[a] * wy[b] * dz[c] * v;
          }
        }
  };

  const Sums sums = tbb::parallel_deterministic_reduce(
      tbb::blocked_range<std::size_t>(0, r.modes, 4096), Sums{},
      [&](const tbb::blocked_range<std::size_t>& range, Sums acc) {
        for (std::size_t i = range.begin(); i < range.end(); ++i) {
          const std::size_t k = order[i];
          const std::size_t x = k % d[0], y = (k / d[0]) % d[1], z = k / (d[0] * d[1]);
          const Eigen::Vector3d w(signed_index(x, d[0]) / s.length.x(), signed_index(y, d[1]) / s.length.y(),
                                  signed_index(z, d[2]) / s.length.z());
          // term = W_k e^{2 pi i w.tau} S2(w'), W_k = S1(w_k) dw, w' = -R^T w (seed 000 eq. 10).
          const Cd e = Cd(s.part1.rho[k]) * dw * std::polar(1.0, 2 * M_PI * w.dot(tau));
          const Eigen::Vector3d wp = -(R.transpose() * w);
          Cd v[4];
          sample(wp.cwiseProduct(s.length), v);
          const Cd term = e * v[0];
          acc.v[0] += term.real();
          acc.v[1] += term.imag();
          if (options.force || torque)  // Re(2 pi i w term), eq. 11
            for (int a = 0; a < 3; ++a) acc.v[2 + a] += -2 * M_PI * term.imag() * w[a];
          if (torque) {  // Re[e (grad S2(w') x w')] in part 2's frame: dE/dtheta of the interpolant
            const Eigen::Vector3d g_re((e * v[1]).real() * s.length.x(), (e * v[2]).real() * s.length.y(),
                                       (e * v[3]).real() * s.length.z());
            const Eigen::Vector3d t = g_re.cross(wp);
            for (int a = 0; a < 3; ++a) acc.v[5 + a] += t[a];
          }
        }
        return acc;
      },
      [](Sums a, const Sums& b) { return a += b; });

  r.score = {sums.v[0], sums.v[1]};
  r.energy = -sums.v[0];
  const Eigen::Vector3d force(sums.v[2], sums.v[3], sums.v[4]);
  if (options.force) r.force = force;
  // About part 2's origin: the box centre's lever arm R c2 added (the centre turns with R).
  if (torque) r.torque = R * Eigen::Vector3d(sums.v[5], sums.v[6], sums.v[7]) + (R * s.part2.centre).cross(force);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

}  // namespace snapfit
