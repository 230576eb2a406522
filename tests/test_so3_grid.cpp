// The SO(3) grid (core/so3_grid.h) against closed forms: Haar measure of balls about a
// rotation, equal areas on S^2, and a brute-force covering radius over random rotations.
#include <cmath>
#include <doctest/doctest.h>
#include <random>

#include "core/so3_grid.h"
#include "snapfit/error.h"

using namespace snapfit;

namespace {

Eigen::Quaterniond random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n;
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized();
}

}  // namespace

TEST_CASE("so3 grid: equal-area sphere points are unit, start and end at the poles, one per cell") {
  for (std::size_t n : {1, 2, 3, 12, 47, 100, 613}) {
    const auto p = equal_area_sphere_points(n);
    CHECK(p.size() == n);
    for (const auto& v : p) CHECK(v.norm() == doctest::Approx(1.0).epsilon(1e-12));
    CHECK(p.front().z() == doctest::Approx(1.0));
    if (n > 1) CHECK(p.back().z() == doctest::Approx(-1.0));
  }
  // Equal areas: the share of 400k uniform directions nearest each point is about 1/n.
  const std::size_t n = 100;
  const auto p = equal_area_sphere_points(n);
  std::mt19937 rng(7);
  std::normal_distribution<double> g;
  std::vector<double> share(n, 0.0);
  const int samples = 400000;
  for (int s = 0; s < samples; ++s) {
    const Eigen::Vector3d d = Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized();
    std::size_t best = 0;
    for (std::size_t i = 1; i < n; ++i)
      if (p[i].dot(d) > p[best].dot(d)) best = i;
    share[best] += 1.0 / samples;
  }
  for (double s : share) CHECK(s == doctest::Approx(1.0 / n).epsilon(0.35));  // Voronoi cells, not the partition's
  CHECK_THROWS_AS(equal_area_sphere_points(0), Error);
}

TEST_CASE("so3 grid: holds the identity and is uniform (Haar measure of balls about random rotations)") {
  const So3Grid grid = so3_grid_for_step(20.0 * M_PI / 180.0);
  CHECK(grid.rotations.size() == grid.base_cells * grid.psi_steps);
  CHECK(rotation_distance(grid.rotations.front(), Eigen::Quaterniond::Identity()) < 1e-12);
  // Share of grid rotations within angle a of a centre = Haar measure (a - sin a) / pi.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::Quaterniond centre = random_rotation(rng);
    for (double a : {0.8, 1.5, 2.4}) {
      double inside = 0;
      for (const auto& q : grid.rotations) inside += rotation_distance(centre, q) <= a;
      CHECK(inside / double(grid.rotations.size()) == doctest::Approx((a - std::sin(a)) / M_PI).epsilon(0.08));
    }
  }
  // No two rotations coincide (q and -q included).
  double closest = M_PI;
  for (std::size_t i = 0; i < grid.rotations.size(); ++i)
    for (std::size_t j = i + 1; j < grid.rotations.size(); ++j)
      closest = std::min(closest, rotation_distance(grid.rotations[i], grid.rotations[j]));
  CHECK(closest > 0.3 * grid.step_rad);
  CHECK_THROWS_AS(so3_grid_for_step(0), Error);
  CHECK_THROWS_AS(so3_grid_for_count(0), Error);
}

TEST_CASE("so3 grid: --rotations N gives about N, and the covering radius is at least a brute-force one") {
  for (std::size_t n : {72, 576, 4000}) {
    const So3Grid g = so3_grid_for_count(n);
    CHECK(double(g.rotations.size()) == doctest::Approx(double(n)).epsilon(0.2));
  }
  const So3Grid grid = so3_grid_for_count(300);
  const double radius = so3_covering_radius(grid, 20000);
  // Brute force: the largest nearest-grid angle of 20k random rotations (every grid rotation tried).
  std::mt19937 rng(3);
  double brute = 0;
  for (int s = 0; s < 20000; ++s) {
    const Eigen::Quaterniond q = random_rotation(rng);
    double nearest = M_PI;
    for (const auto& g : grid.rotations) nearest = std::min(nearest, rotation_distance(q, g));
    brute = std::max(brute, nearest);
  }
  MESSAGE("300 rotations: covering radius " << radius * 180 / M_PI << " deg, random probes " << brute * 180 / M_PI);
  CHECK(radius >= brute - 1e-9);
  CHECK(radius < brute * 1.25);                                                 // both converge to the same radius
  CHECK(so3_covering_radius(so3_grid_for_count(2400), 20000) < 0.65 * radius);  // 8x the rotations: about half
  CHECK(rotation_distance(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized())),
                          Eigen::Quaterniond(-Eigen::Quaterniond::Identity().coeffs())) == doctest::Approx(0.7));
}
