#include "mesh/triangle_refine.h"

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <tbb/parallel_for.h>

#include "snapfit/error.h"

namespace snapfit {
namespace {

using Vec3 = Eigen::Vector3d;

double centroid_radius(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 m = (a + b + c) / 3.0;
  return std::sqrt(std::max({(a - m).squaredNorm(), (b - m).squaredNorm(), (c - m).squaredNorm()}));
}

// Number of pieces bisection produces for one triangle (same rule as split()).
std::size_t piece_count(const Vec3& a, const Vec3& b, const Vec3& c, double max_radius, int depth = 0) {
  if (centroid_radius(a, b, c) <= max_radius || depth >= 60) return 1;
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  if (ab >= bc && ab >= ca)
    return piece_count(a, (a + b) / 2, c, max_radius, depth + 1) +
           piece_count((a + b) / 2, b, c, max_radius, depth + 1);
  if (bc >= ca)
    return piece_count(b, (b + c) / 2, a, max_radius, depth + 1) +
           piece_count((b + c) / 2, c, a, max_radius, depth + 1);
  return piece_count(c, (c + a) / 2, b, max_radius, depth + 1) + piece_count((c + a) / 2, a, b, max_radius, depth + 1);
}

// Appends the pieces of (a, b, c), keeping its orientation, at out[at...].
void split(const Vec3& a, const Vec3& b, const Vec3& c, double max_radius, Vec3* out, std::size_t& at, int depth = 0) {
  if (centroid_radius(a, b, c) <= max_radius || depth >= 60) {
    out[at++] = a;
    out[at++] = b;
    out[at++] = c;
    return;
  }
  const double ab = (b - a).squaredNorm(), bc = (c - b).squaredNorm(), ca = (a - c).squaredNorm();
  if (ab >= bc && ab >= ca) {
    split(a, (a + b) / 2, c, max_radius, out, at, depth + 1);
    split((a + b) / 2, b, c, max_radius, out, at, depth + 1);
  } else if (bc >= ca) {
    split(b, (b + c) / 2, a, max_radius, out, at, depth + 1);
    split((b + c) / 2, c, a, max_radius, out, at, depth + 1);
  } else {
    split(c, (c + a) / 2, b, max_radius, out, at, depth + 1);
    split((c + a) / 2, a, b, max_radius, out, at, depth + 1);
  }
}

}  // namespace

Mesh refine_triangles(const Mesh& mesh, double max_radius, std::size_t max_triangles) {
  if (!(max_radius > 0) || !std::isfinite(max_radius)) throw Error("refinement radius must be a positive number");
  const std::size_t n = mesh.triangles.size();
  auto corner = [&](std::size_t t, int k) -> const Vec3& { return mesh.vertices[mesh.triangles[t][k]]; };
  // A piece within a ball of radius r has area at most (3 sqrt 3 / 4) r^2 (the
  // inscribed equilateral triangle), so area / that bounds the piece count from below:
  // refuse at once rather than after counting billions of pieces.
  double area = 0;
  for (std::size_t t = 0; t < n; ++t)
    area += 0.5 * (corner(t, 1) - corner(t, 0)).cross(corner(t, 2) - corner(t, 0)).norm();
  const double at_least = area / (1.299038105676658 * max_radius * max_radius);
  if (at_least > static_cast<double>(max_triangles))
    throw Error("refining " + std::to_string(n) + " triangles to radius " + std::to_string(max_radius) +
                " gives at least " + std::to_string(static_cast<unsigned long long>(at_least)) + " pieces, more than " +
                std::to_string(max_triangles));
  // Count first, so every triangle writes its pieces at a known offset in parallel.
  std::vector<std::size_t> offset(n + 1, 0);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t t) {
    offset[t + 1] = piece_count(corner(t, 0), corner(t, 1), corner(t, 2), max_radius);
  });
  for (std::size_t t = 0; t < n; ++t) offset[t + 1] += offset[t];
  if (offset[n] > max_triangles)
    throw Error("refining " + std::to_string(n) + " triangles to radius " + std::to_string(max_radius) + " gives " +
                std::to_string(offset[n]) + " pieces, more than " + std::to_string(max_triangles));
  Mesh out;
  out.vertices.resize(3 * offset[n]);
  out.triangles.resize(offset[n]);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t t) {
    std::size_t at = 3 * offset[t];
    split(corner(t, 0), corner(t, 1), corner(t, 2), max_radius, out.vertices.data(), at);
    for (std::size_t p = offset[t]; p < offset[t + 1]; ++p)
      out.triangles[p] =
          Eigen::Vector3i(static_cast<int>(3 * p), static_cast<int>(3 * p + 1), static_cast<int>(3 * p + 2));
  });
  return out;
}

}  // namespace snapfit
