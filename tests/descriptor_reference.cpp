// Brute-force double-precision references for the descriptor tests
// (descriptor_reference.h). Written from the definitions, independently of kernels/*.cl.
#include "tests/descriptor_reference.h"
#include "tests/test_support.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/parallel_for.h>

namespace snapfit::test {

namespace {

using Eigen::Vector3d;

double segment_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d e = b - a;
  const double len2 = e.squaredNorm();
  if (len2 == 0.0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(e) / len2, 0.0, 1.0);
  return (p - (a + t * e)).norm();
}

// Angle between two (unnormalized) vectors, accurate for small and near-pi angles.
double arc(const Vector3d& u, const Vector3d& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); }

}  // namespace

double reference_point_triangle_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  const double scale2 = std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (n2 > 1e-24 * scale2 * scale2) {
    // Project p onto the plane; if the projection is inside the triangle (all three
    // sub-triangle orientations agree with n), the distance is the plane distance.
    const Vector3d q = p - ((p - a).dot(n) / n2) * n;
    const double ua = (c - b).cross(q - b).dot(n);
    const double ub = (a - c).cross(q - c).dot(n);
    const double uc = (b - a).cross(q - a).dot(n);
    if (ua >= 0 && ub >= 0 && uc >= 0) return std::abs((p - a).dot(n)) / std::sqrt(n2);
  }
  // Otherwise the nearest point lies on the boundary.
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

double reference_distance(const Mesh& mesh, const Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : mesh.triangles)
    best = std::min(
        best, reference_point_triangle_distance(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]));
  return best;
}

double reference_solid_angle(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d u = a - p, v = b - p, w = c - p;
  const double det = u.dot(v.cross(w));
  if (det == 0.0 || u.squaredNorm() == 0.0 || v.squaredNorm() == 0.0 || w.squaredNorm() == 0.0) return 0.0;
  // l'Huilier: tan(E/4) = sqrt(tan(s/2) tan((s-A)/2) tan((s-B)/2) tan((s-C)/2)),
  // A, B, C the arc lengths of the spherical triangle, s their half sum, E the excess.
  const double A = arc(v, w), B = arc(w, u), C = arc(u, v);
  const double s = 0.5 * (A + B + C);
  const double t =
      std::tan(0.5 * s) * std::tan(0.25 * (B + C - A)) * std::tan(0.25 * (C + A - B)) * std::tan(0.25 * (A + B - C));
  const double excess = 4.0 * std::atan(std::sqrt(std::max(t, 0.0)));
  return det > 0 ? excess : -excess;
}

double reference_winding(const Mesh& mesh, const Vector3d& p, double* abs_sum) {
  double sum = 0, total = 0;
  for (const auto& t : mesh.triangles) {
    const double o = reference_solid_angle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
    sum += o;
    total += std::abs(o);
  }
  if (abs_sum) *abs_sum = total / (4 * kPi);
  return sum / (4 * kPi);
}

namespace {

// 7-point degree-5 rule on a triangle (Radon 1948; Strang & Fix; Dunavant 1985 n=5):
// barycentric points and weights (summing to 1) in closed form with sqrt(15).
struct Rule7 {
  double bary[7][3];
  double weight[7];
  Rule7() {
    const double r15 = std::sqrt(15.0);
    const double a1 = (9 - 2 * r15) / 21, b1 = (6 + r15) / 21, w1 = (155 + r15) / 1200;
    const double a2 = (9 + 2 * r15) / 21, b2 = (6 - r15) / 21, w2 = (155 - r15) / 1200;
    bary[0][0] = bary[0][1] = bary[0][2] = 1.0 / 3;
    weight[0] = 9.0 / 40;
    for (int k = 0; k < 3; ++k) {
      for (int j = 0; j < 3; ++j) {
        bary[1 + k][j] = j == k ? a1 : b1;
        bary[4 + k][j] = j == k ? a2 : b2;
      }
      weight[1 + k] = w1;
      weight[4 + k] = w2;
    }
  }
};

const Rule7& rule7() {
  static const Rule7 rule;
  return rule;
}

struct DensityIntegrator {
  Vector3d p;
  double xi, sigma, inv_two_sigma2, g0, x_cut, negligible;
  ReferenceQuadrature quad;
  double h = 0;  // plane height of p for the current triangle: (q - p).n, constant on it
  double sum = 0, err = 0;

  double g(double x) const { return g0 * std::exp(-x * x * inv_two_sigma2); }

  // Q7 of g(eta/xi - 1) h / eta^3 over the piece (area `area`).
  double rule(const Vector3d& a, const Vector3d& b, const Vector3d& c, double area) const {
    const Rule7& r = rule7();
    double acc = 0;
    for (int k = 0; k < 7; ++k) {
      const Vector3d q = r.bary[k][0] * a + r.bary[k][1] * b + r.bary[k][2] * c;
      const double eta = (q - p).norm();
      acc += r.weight[k] * g(eta / xi - 1) / (eta * eta * eta);
    }
    return acc * h * area;
  }

  void piece(const Vector3d& a, const Vector3d& b, const Vector3d& c, double area, int depth) {
    const Vector3d cen = (a + b + c) / 3.0;
    const double r = std::sqrt(std::max({(a - cen).squaredNorm(), (b - cen).squaredNorm(), (c - cen).squaredNorm()}));
    const double D = (cen - p).norm();
    const double eta_min = std::max(D - r, std::abs(h));  // every point of the plane is >= |h| away
    const double x_min = eta_min / xi - 1, x_max = (D + r) / xi - 1;
    const double omega_bound =
        eta_min > 0 ? std::abs(h) * area / (eta_min * eta_min * eta_min) : std::numeric_limits<double>::infinity();
    if (x_min > x_cut) {  // g below g(12 sigma) on the whole piece
      err += g(x_min) * omega_bound;
      return;
    }
    const double g_max = g(x_min > 0 ? x_min : (x_max < 0 ? x_max : 0.0));
    if (g_max * omega_bound < negligible) {
      err += g_max * omega_bound;
      return;
    }
    if (r <= quad.distance_ratio * D && r <= quad.gaussian_ratio * sigma * xi) {
      const Vector3d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
      const double q0 = rule(a, b, c, area);
      const double q1 = rule(a, ab, ca, area / 4) + rule(ab, b, bc, area / 4) + rule(ca, bc, c, area / 4) +
                        rule(ab, bc, ca, area / 4);
      sum += q1;
      err += std::abs(q1 - q0);
      return;
    }
    if (depth >= quad.max_depth) {
      // g(x_c) times the exact solid angle; |g(x) - g(x_c)| <= its range on the piece.
      const double omega = reference_solid_angle(p, a, b, c);
      const double gc = g(D / xi - 1);
      const double lo = std::max(D - r, 0.0) / xi - 1;
      double dev = std::max(std::abs(g(lo) - gc), std::abs(g(x_max) - gc));
      if (lo <= 0 && x_max >= 0) dev = std::max(dev, g0 - gc);
      sum += gc * omega;
      err += dev * std::abs(omega);
      return;
    }
    const Vector3d ab = 0.5 * (a + b), bc = 0.5 * (b + c), ca = 0.5 * (c + a);
    piece(a, ab, ca, area / 4, depth + 1);
    piece(ab, b, bc, area / 4, depth + 1);
    piece(ca, bc, c, area / 4, depth + 1);
    piece(ab, bc, ca, area / 4, depth + 1);
  }
};

}  // namespace

double reference_skeletal_density(const Mesh& mesh, const Vector3d& p, double xi_abs, double sigma,
                                  double* error_estimate, const ReferenceQuadrature& quadrature) {
  DensityIntegrator in;
  in.p = p;
  in.xi = xi_abs;
  in.sigma = sigma;
  in.inv_two_sigma2 = 1.0 / (2 * sigma * sigma);
  in.g0 = 1.0 / (std::sqrt(2 * kPi) * sigma);
  in.x_cut = 12 * sigma;
  in.negligible = 1e-17 * in.g0;
  in.quad = quadrature;
  for (const auto& t : mesh.triangles) {
    const Vector3d& a = mesh.vertices[t[0]];
    const Vector3d& b = mesh.vertices[t[1]];
    const Vector3d& c = mesh.vertices[t[2]];
    const Vector3d n = (b - a).cross(c - a);
    const double n_len = n.norm();
    if (n_len == 0.0) continue;  // zero area: contributes nothing
    in.h = (a - p).dot(n / n_len);
    if (in.h == 0.0) continue;  // p in the triangle's plane: the integrand vanishes (principal value)
    in.piece(a, b, c, 0.5 * n_len, 0);
  }
  if (error_estimate) *error_estimate = in.err;
  return in.sum;
}

std::vector<double> reference_skeletal_density(const Mesh& mesh, const std::vector<Vector3d>& points,
                                               const std::vector<double>& xi_abs, double sigma,
                                               std::vector<double>* error_estimates,
                                               const ReferenceQuadrature& quadrature) {
  std::vector<double> out(points.size()), err(points.size());
  tbb::parallel_for(std::size_t(0), points.size(), [&](std::size_t i) {
    out[i] = reference_skeletal_density(mesh, points[i], xi_abs[i], sigma, &err[i], quadrature);
  });
  if (error_estimates) *error_estimates = std::move(err);
  return out;
}

bool reference_ray_crossings(const Mesh& mesh, const Vector3d& p, const Vector3d& dir, int* parity, int* signed_count,
                             double guard) {
  const Vector3d d = dir.normalized();
  int count = 0, sum = 0;
  for (const auto& t : mesh.triangles) {
    const Vector3d& a = mesh.vertices[t[0]];
    const Vector3d& b = mesh.vertices[t[1]];
    const Vector3d& c = mesh.vertices[t[2]];
    const Vector3d n = (b - a).cross(c - a);
    const double n_len = n.norm();
    if (n_len == 0.0) continue;  // degenerate: no area to cross (its edges belong to neighbours)
    const double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    const double dn = d.dot(n) / n_len;        // cosine between the ray and the normal
    const double hp = (a - p).dot(n) / n_len;  // plane height: the ray meets the plane at t = hp / dn
    if (std::abs(dn) <= guard) {
      if (std::abs(hp) <= guard * size) return false;  // ray (nearly) in the plane
      continue;                                        // parallel, off the plane
    }
    const double tt = hp / dn;
    if (std::abs(tt) <= guard * size) return false;  // p (nearly) on the plane: on the surface or ambiguous
    if (tt < 0) continue;
    const Vector3d q = p + tt * d;
    // Barycentric coordinates of q from signed sub-areas, normalized by the full area.
    const double n2 = n_len * n_len;
    const double ua = (c - b).cross(q - b).dot(n) / n2;
    const double ub = (a - c).cross(q - c).dot(n) / n2;
    const double uc = 1.0 - ua - ub;
    const double m = std::min({ua, ub, uc});
    if (std::abs(m) <= guard * 1e3) return false;  // through (or next to) an edge or vertex
    if (m < 0) continue;
    ++count;
    sum += dn > 0 ? 1 : -1;  // leaving through the front (outward normal): from inside
  }
  if (parity) *parity = count % 2;
  if (signed_count) *signed_count = sum;
  return true;
}

}  // namespace snapfit::test
