#pragma once
// Small meshes shared by the geometry tests.
#include <random>

#include "mesh/mesh.h"
#include "mesh/procedural/procedural_parts.h"

namespace snapfit::test {

// The procedural peg (64 segments): a closed, outward-oriented prism.
inline Mesh peg_mesh(double radius = 1, double length = 3) {
  return make_procedural_part({"peg", {{"radius", radius}, {"length", length}}, {}});
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
