#pragma once
// Small meshes shared by the geometry tests.
#include <cmath>
#include <random>

#include "mesh/mesh.h"
#include "mesh/procedural/procedural_parts.h"

namespace snapfit::test {

// The procedural peg (64 segments): a closed, outward-oriented prism.
inline Mesh peg_mesh(double radius = 1, double length = 3) {
  return make_procedural_part({"peg", {{"radius", radius}, {"length", length}}, {}});
}

// Adds the quad p0 p1 p2 p3 (a planar convex loop) as two triangles wound so that their
// normal points along `outward`.
inline void add_quad(Mesh& m, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                     const Eigen::Vector3d& p3, const Eigen::Vector3d& outward) {
  const int base = static_cast<int>(m.vertices.size());
  for (const Eigen::Vector3d& p : {p0, p1, p2, p3}) m.vertices.push_back(p);
  if ((p1 - p0).cross(p2 - p0).dot(outward) > 0) {
    m.triangles.emplace_back(base, base + 1, base + 2);
    m.triangles.emplace_back(base, base + 2, base + 3);
  } else {
    m.triangles.emplace_back(base, base + 2, base + 1);
    m.triangles.emplace_back(base, base + 3, base + 2);
  }
}

// The axis-aligned box [lo, hi] with outward normals (unindexed quads).
inline Mesh box_mesh(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Mesh m;
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      Eigen::Vector3d corner[4];
      for (int k = 0; k < 4; ++k) {
        corner[k][a] = side ? hi[a] : lo[a];
        corner[k][b] = (k == 1 || k == 2) ? hi[b] : lo[b];
        corner[k][c] = (k >= 2) ? hi[c] : lo[c];
      }
      add_quad(m, corner[0], corner[1], corner[2], corner[3], (side ? 1.0 : -1.0) * Eigen::Vector3d::Unit(a));
    }
  return m;
}

// A cup: the box [-outer, outer]^2 x [-height, 0] minus the open-topped square cavity
// [-inner, inner]^2 x [-depth, 0] (inner < outer, depth < height); closed, outward normals.
inline Mesh cup_mesh(double outer, double inner, double depth, double height) {
  Mesh m;
  const auto v = [](double x, double y, double z) { return Eigen::Vector3d(x, y, z); };
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  for (int k = 0; k < 4; ++k) {  // the four sides, each turned by k quarter turns about z
    const double c = std::round(std::cos(k * M_PI / 2)), s = std::round(std::sin(k * M_PI / 2));
    const auto turn = [&](const Eigen::Vector3d& p) {
      return Eigen::Vector3d(c * p.x() - s * p.y(), s * p.x() + c * p.y(), p.z());
    };
    const Eigen::Vector3d out = turn(Eigen::Vector3d::UnitX());
    add_quad(m, turn(v(inner, -inner, 0)), turn(v(outer, -outer, 0)), turn(v(outer, outer, 0)),
             turn(v(inner, inner, 0)), up);
    add_quad(m, turn(v(outer, -outer, -height)), turn(v(outer, outer, -height)), turn(v(outer, outer, 0)),
             turn(v(outer, -outer, 0)), out);
    add_quad(m, turn(v(inner, -inner, -depth)), turn(v(inner, inner, -depth)), turn(v(inner, inner, 0)),
             turn(v(inner, -inner, 0)), -out);
  }
  add_quad(m, v(-outer, -outer, -height), v(outer, -outer, -height), v(outer, outer, -height),
           v(-outer, outer, -height), -up);
  add_quad(m, v(-inner, -inner, -depth), v(inner, -inner, -depth), v(inner, inner, -depth), v(-inner, inner, -depth),
           up);
  return m;
}

// n unindexed random triangles: centres uniform in [-half_extent, half_extent]^3,
// corners within +-spread of their centre on each axis.
inline Mesh random_soup(int n, unsigned seed, double half_extent, double spread) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> centre(-half_extent, half_extent), offset(-spread, spread);
  Mesh m;
  for (int t = 0; t < n; ++t) {
    const Eigen::Vector3d c(centre(rng), centre(rng), centre(rng));
    for (int k = 0; k < 3; ++k) m.vertices.push_back(c + Eigen::Vector3d(offset(rng), offset(rng), offset(rng)));
    m.triangles.emplace_back(3 * t, 3 * t + 1, 3 * t + 2);
  }
  return m;
}

}  // namespace snapfit::test
