#pragma once
// Independent double-precision brute-force references for the shape descriptors
// (docs/design.md "Shape descriptors"; seed 000 sec. 2.3, 3.1), used only by the tests.
// No hierarchy, no far-field expansion, no code shared with kernels/*.cl:
//   reference_distance          exact point-triangle distance (plane projection, then
//                               the three edges as segments), minimum over triangles
//   reference_solid_angle       signed solid angle of one triangle by l'Huilier's
//                               theorem (spherical excess from the three arc lengths)
//   reference_winding           (1/4pi) * sum of those solid angles
//   reference_skeletal_density  adaptive 4-way subdivision + 7-point degree-5 rule
//   reference_ray_crossings     signed ray-triangle crossings (ray parity)
// Sign conventions as in the engine: triangles counter-clockwise seen from outside,
// solid angle positive when p is behind the face, so w = 1 inside a closed mesh and
// s > 0 inside, s < 0 outside.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "mesh/mesh.h"

namespace snapfit::test {

// Exact distance from p to triangle (a, b, c) (degenerate triangles: distance to the
// edges), and from p to the whole mesh (minimum over triangles; +inf for no triangles).
double reference_point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c);
double reference_distance(const Mesh& mesh, const Eigen::Vector3d& p);

// Signed solid angle of triangle (a, b, c) seen from p, in [-2pi, 2pi]: positive when
// p is on the side opposite to the normal (b - a) x (c - a).
double reference_solid_angle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                             const Eigen::Vector3d& c);

// w(p) = (1/4pi) sum of signed solid angles. If `abs_sum` is given it receives
// (1/4pi) sum of |solid angle| (a scale for rounding errors of the sum).
double reference_winding(const Mesh& mesh, const Eigen::Vector3d& p, double* abs_sum = nullptr);

// Skeletal density
//   s(p) = integral over the surface of g_sigma(eta/xi_abs - 1) dOmega(q),
//   dOmega = (q - p).n / |q - p|^3 dA,  eta = |q - p|,
//   g_sigma(x) = exp(-x^2 / (2 sigma^2)) / (sqrt(2 pi) sigma).
// Every triangle is split 4-way at its edge midpoints until a piece with centroid c,
// circumradius r (around c), D = |c - p| satisfies r <= distance_ratio * D and
// r <= gaussian_ratio * sigma * xi_abs (ReferenceQuadrature); such a leaf is
// integrated with the 7-point degree-5 rule (Radon / Strang-Fix / Dunavant) on the
// piece and on each of its four children, and the children's sum is used.
// Pieces that contribute nothing measurable are skipped: those whose every point has
// x = eta/xi_abs - 1 > 12 sigma, and those whose contribution is below 1e-17 * g(0)
// (bounded by g_max * |h| A / eta_min^3, h = plane height of p, eta_min a lower bound
// of eta on the piece). Pieces still unresolved at max_depth (only for p within
// ~1e-7 of the triangle's size of the surface) use g(x_c) times the piece's exact solid
// angle.
//
// *error_estimate (if given) receives the sum of
//   - |Q7(piece) - sum of Q7(children)| over the leaves: an estimate of the error of
//     Q7(piece); the value returned uses the children, whose error for a smooth
//     integrand is ~2^-6 of that, so this term is conservative, but it is an
//     estimate, not a rigorous bound;
//   - g(x_min) * |h| A / eta_min^3 for every skipped piece (a rigorous bound of what
//     was dropped);
//   - max |g(x) - g(x_c)| * |solid angle| for the depth-capped pieces (rigorous).
// The defaults come from a convergence study (a 16-segment peg, 40 random points at
// distances 0.01..1.5 from a unit-radius surface, sigma 0.25 and 0.5): against the
// result with ratios (0.05, 0.1) the maximum relative difference was 1.4e-11 (sigma
// 0.25) and 3.7e-11 (sigma 0.5), with the error estimate 90-200 times the actual
// difference; (0.25, 0.5) gave 1.2e-9. tests/test_descriptors.cpp also checks the
// result against an independent polar-coordinate integral over a square (agreement
// within 1e-8 relative, sigma 0.25 to 2, with the estimate above the actual error).
// Cost: ~20 ms per point for a 64-triangle peg at sigma 0.25 on one core.
struct ReferenceQuadrature {
  double distance_ratio = 0.2;  // r <= distance_ratio * D
  double gaussian_ratio = 0.3;  // r <= gaussian_ratio * sigma * xi_abs
  int max_depth = 24;
};
double reference_skeletal_density(const Mesh& mesh, const Eigen::Vector3d& p, double xi_abs, double sigma,
                                  double* error_estimate = nullptr, const ReferenceQuadrature& quadrature = {});

// The same for many points at once (TBB parallel over points). xi_abs[i] belongs to
// points[i]; error_estimates (if given) is resized and filled.
std::vector<double> reference_skeletal_density(const Mesh& mesh, const std::vector<Eigen::Vector3d>& points,
                                               const std::vector<double>& xi_abs, double sigma,
                                               std::vector<double>* error_estimates = nullptr,
                                               const ReferenceQuadrature& quadrature = {});

// Crossings of the ray p + t dir (t > 0) with the mesh, in double: +1 for a triangle
// crossed from its back (inside) to its front, -1 the other way. Returns false when
// the ray passes within a relative `guard` of a triangle's edge or vertex, or lies in
// a triangle's plane, so the count would be ambiguous. `parity` receives the number of
// crossings mod 2, `signed_count` (if given) the signed sum (the winding number along
// the ray for a closed mesh).
bool reference_ray_crossings(const Mesh& mesh, const Eigen::Vector3d& p, const Eigen::Vector3d& dir, int* parity,
                             int* signed_count = nullptr, double guard = 1e-9);

}  // namespace snapfit::test
