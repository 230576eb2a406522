// Exact point-to-mesh distances (mesh/mesh_distance.h) against closed forms on a box and
// the procedural peg, and the closest point on a triangle against dense sampling.
#include <doctest/doctest.h>
#include <random>

#include "mesh/mesh_distance.h"
#include "tests/test_meshes.h"

using namespace snapfit;

TEST_CASE("mesh distance: closest point on a triangle matches dense barycentric sampling") {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2, 2);
  const auto random_point = [&] { return Eigen::Vector3d(u(rng), u(rng), u(rng)); };
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::Vector3d a = random_point(), b = random_point(), c = random_point(), p = 2 * random_point();
    const Eigen::Vector3d q = closest_point_on_triangle(p, a, b, c);
    double sampled = 1e300;
    const int n = 400;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j)
        sampled = std::min(sampled, (a + (b - a) * (double(i) / n) + (c - a) * (double(j) / n) - p).norm());
    // The sampled minimum is above the exact one by at most the sampling step.
    const double step = std::max({(b - a).norm(), (c - a).norm(), (c - b).norm()}) / n;
    CHECK((q - p).norm() <= sampled + 1e-12);
    CHECK((q - p).norm() >= sampled - step);
  }
}

TEST_CASE("mesh distance: signed distance to a box and to the peg in closed form") {
  const Mesh box = test::box_mesh(Eigen::Vector3d(-1, -2, -3), Eigen::Vector3d(1, 2, 3));
  CHECK(signed_distance(box, Eigen::Vector3d(0.2, 0.1, -0.5)) == doctest::Approx(-0.8));
  CHECK(signed_distance(box, Eigen::Vector3d(0, 1.7, 0)) == doctest::Approx(-0.3));
  CHECK(signed_distance(box, Eigen::Vector3d(2.5, 0, 0)) == doctest::Approx(1.5));
  CHECK(signed_distance(box, Eigen::Vector3d(2, 3, 4)) == doctest::Approx(std::sqrt(3.0)));
  CHECK(winding_number(box, Eigen::Vector3d(0.3, -1, 2)) == doctest::Approx(1).epsilon(1e-9));
  CHECK(std::abs(winding_number(box, Eigen::Vector3d(5, 0, 0))) < 1e-9);
  // The 64-gon peg of radius 1, length 3: on its axis the side is the apothem cos(pi/64) away.
  const Mesh peg = test::peg_mesh(1, 3);
  CHECK(signed_distance(peg, Eigen::Vector3d(0, 0, 1.5)) == doctest::Approx(-std::cos(M_PI / 64)));
  CHECK(signed_distance(peg, Eigen::Vector3d(0, 0, 0.25)) == doctest::Approx(-0.25));
  CHECK(signed_distance(peg, Eigen::Vector3d(0, 0, 3.4)) == doctest::Approx(0.4));
}

TEST_CASE("mesh distance: the indexed signed distance equals brute force on the three-peg cover") {
  // The shipped three-peg cover (filleted holes, scenes/three_pegs.json's parameters).
  const Mesh cover =
      make_procedural_part({"three_peg_cover",
                            {{"cell", 20}, {"base_thickness", 8}, {"cover_thickness", 6}, {"segments", 32}},
                            {{"peg_radii", {3, 4.5, 6}}, {"fillet_radii", {1, 1.5, 2}}, {"peg_heights", {8, 10, 12}}}});
  const MeshDistanceIndex index(cover);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1);
  const Eigen::Vector3d lo = index.box_min() - Eigen::Vector3d::Constant(2);
  const Eigen::Vector3d span = index.box_max() - index.box_min() + Eigen::Vector3d::Constant(4);
  int inside = 0;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d p = lo + span.cwiseProduct(Eigen::Vector3d(u(rng), u(rng), u(rng)));
    const double exact = signed_distance(cover, p);
    CAPTURE(p.transpose());
    CHECK(index.signed_distance(p) == doctest::Approx(exact).epsilon(1e-12));
    inside += exact < 0;
  }
  CHECK(inside > 10);  // the sample reaches inside the part too
}

TEST_CASE("mesh distance: the indexed distance equals brute force far outside the part's box") {
  // Points up to 5 part sizes off along every axis and diagonal: the search stops early
  // there, on a bound that counts how far outside the grid the point lies.
  const Mesh peg = test::peg_mesh(5, 30);
  const MeshDistanceIndex index(peg);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-150, 150);
  for (int i = 0; i < 300; ++i) {
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    if (i % 3 == 0) p.x() = 0.1 * p.x();  // beside the peg's axis, far above or below it
    if (i % 3 == 1) p.z() = 15 + 0.1 * p.z();  // level with its side, far out
    CAPTURE(p.transpose());
    CHECK(index.distance(p) == doctest::Approx(std::abs(signed_distance(peg, p))).epsilon(1e-12));
  }
}
