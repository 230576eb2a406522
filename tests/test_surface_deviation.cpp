// The surface deviation between two placements of one part (mesh/surface_deviation.h)
// against closed forms: a translation, turns of a round and a square peg about their
// axis, and a tilt.
#include <cmath>
#include <doctest/doctest.h>

#include "mesh/surface_deviation.h"
#include "snapfit/error.h"
#include "tests/test_meshes.h"

using namespace snapfit;

namespace {

Pose turned(const Eigen::Vector3d& axis, double degrees, const Eigen::Vector3d& translation = Eigen::Vector3d::Zero()) {
  Pose p;
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(degrees * M_PI / 180, axis.normalized()));
  p.translation = translation;
  return p;
}

Pose moved(const Eigen::Vector3d& d) { return turned(Eigen::Vector3d::UnitZ(), 0, d); }

// A square peg: the box [-b, b]^2 x [0, h], its axis +z through the origin.
Mesh square_peg(double b, double h) { return test::box_mesh(Eigen::Vector3d(-b, -b, 0), Eigen::Vector3d(b, b, h)); }

// A prism over the scalene triangle (0, 0), (4, 0), (1, 2), z in [0, 1]: no symmetry, so a
// turn and its inverse move its surface differently.
Mesh scalene_prism() {
  Mesh m;
  for (double z : {0.0, 1.0})
    for (const Eigen::Vector2d& q : {Eigen::Vector2d(0, 0), Eigen::Vector2d(4, 0), Eigen::Vector2d(1, 2)})
      m.vertices.emplace_back(q.x(), q.y(), z);
  m.triangles = {{0, 2, 1}, {3, 4, 5}};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    m.triangles.emplace_back(i, j, j + 3);
    m.triangles.emplace_back(i, j + 3, i + 3);
  }
  return m;
}

}  // namespace

TEST_CASE("surface deviation: a translation by d moves a convex part's surface by |d|") {
  // The support point in d's direction is a corner (box) or a rim vertex (peg), always
  // sampled: the measured distance is |d| to rounding.
  const Mesh box = square_peg(2, 6), peg = test::peg_mesh(5, 30);
  const Pose base = turned(Eigen::Vector3d(1, 2, 3), 25, Eigen::Vector3d(4, -1, 7));
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d(0.3, -0.2, 0.5), Eigen::Vector3d(0, 0, -0.05), Eigen::Vector3d(-1.5, 0.7, 0.1)}) {
    for (const Mesh* mesh : {&box, &peg}) {
      const SurfaceDeviation dev = surface_deviation(*mesh, base, moved(d) * base, 0.5);
      INFO("d = ", d.transpose(), ", measured ", dev.distance);
      CHECK(dev.distance == doctest::Approx(d.norm()).epsilon(1e-9));
    }
  }
  CHECK(surface_deviation(peg, base, base, 0.5).distance < 1e-9);
}

TEST_CASE("surface deviation: a round peg turned about its axis stays within its facets' sagitta") {
  const double radius = 5, length = 30;
  const Mesh peg = test::peg_mesh(radius, length);  // a 64-gon prism
  const double sagitta = radius * (1 - std::cos(M_PI / 64));
  const Pose fit = moved(Eigen::Vector3d(0, 0, -20));
  // A quarter turn maps the 64-gon onto itself.
  const SurfaceDeviation quarter = surface_deviation(peg, fit * turned(Eigen::Vector3d::UnitZ(), 90), fit, 0.3);
  CHECK(quarter.distance < 1e-9);
  // Any other turn puts the rim's vertices between the other's, at most a sagitta out.
  for (double degrees : {37.0, 2.0, 123.4}) {
    const SurfaceDeviation dev = surface_deviation(peg, fit * turned(Eigen::Vector3d::UnitZ(), degrees), fit, 0.3);
    INFO(degrees, " degrees: ", dev.distance, " against the sagitta ", sagitta);
    CHECK(dev.distance <= sagitta + 1e-9);
  }
  // 37 degrees is 6.58 segments: a vertex lands 0.44 degrees from an edge's middle.
  const double at_37 = surface_deviation(peg, turned(Eigen::Vector3d::UnitZ(), 37), Pose{}, 0.3).distance;
  CHECK(at_37 >= 0.9 * sagitta);
}

TEST_CASE("surface deviation: a square peg turned by theta about its axis: b (sqrt 2 sin(45 + theta) - 1)") {
  const double b = 5, h = 30;
  const Mesh peg = square_peg(b, h);
  for (double degrees : {45.0, 10.0, 3.0, -20.0}) {
    const double theta = std::abs(degrees) * M_PI / 180;
    const double expected = b * (std::sqrt(2.0) * std::sin(M_PI / 4 + theta) - 1);
    const SurfaceDeviation dev = surface_deviation(peg, turned(Eigen::Vector3d::UnitZ(), degrees), Pose{}, 0.5);
    INFO(degrees, " degrees: ", dev.distance, " against ", expected);
    CHECK(dev.distance == doctest::Approx(expected).epsilon(1e-9));
    // The farthest sample is on a vertical edge (a corner of the cross-section).
    CHECK(std::abs(dev.where.x()) == doctest::Approx(b));
    CHECK(std::abs(dev.where.y()) == doctest::Approx(b));
  }
  CHECK(b * (std::sqrt(2.0) - 1) == doctest::Approx(2.0710678).epsilon(1e-6));  // the 45-degree figure
}

TEST_CASE("surface deviation: a tilt by theta moves the far end by about the arm times theta") {
  // Tilted about x through the base's centre, the top edge at y = -b swings out by
  // b cos + h sin - b (a sampled corner: the lower bound, met exactly); no point moves
  // farther than its chord 2 sin(theta / 2) |p|, at most sqrt(b^2 + h^2) away.
  const double b = 1, h = 10;
  for (const Mesh& mesh : {square_peg(b, h), test::peg_mesh(b, h)}) {
    for (double degrees : {5.0, 1.0, 0.2}) {
      const double theta = degrees * M_PI / 180;
      const double corner = b * std::cos(theta) + h * std::sin(theta) - b;
      const double chord = 2 * std::sin(theta / 2) * std::hypot(b, h);
      const SurfaceDeviation dev = surface_deviation(mesh, turned(Eigen::Vector3d::UnitX(), degrees), Pose{}, 0.25);
      INFO(degrees, " degrees: ", dev.distance, ", arm x angle ", h * theta, ", bounds ", corner, " .. ", chord);
      CHECK(dev.distance >= corner - 1e-9);
      CHECK(dev.distance <= chord + 1e-9);
      CHECK(dev.distance == doctest::Approx(h * theta).epsilon(0.02));
      CHECK(dev.where.z() == doctest::Approx(h));  // at the far end
    }
  }
}

TEST_CASE("surface deviation: the meter keeps its sample count bounded and refuses what it cannot measure") {
  const Mesh peg = test::peg_mesh(5, 30);
  const SurfaceDeviationMeter fine(peg, 0.01, 2000);  // 0.01 apart would be ~10^7 points
  CHECK(fine.spacing() > 0.5);
  CHECK(fine.samples() < 4000);
  CHECK_THROWS_AS(SurfaceDeviationMeter(Mesh{}, 0.1), Error);
  CHECK_THROWS_AS(SurfaceDeviationMeter(peg, 0), Error);
  CHECK_THROWS_AS(SurfaceDeviationMeter(peg, std::nan("")), Error);
}

TEST_CASE("surface deviation: both sides count, so the distance does not depend on the order of the poses") {
  // Turned 40 degrees about a vertical axis through (3, 1), the prism's one-sided
  // distances differ (one side's farthest sample is where_at_a, the other's is not).
  const Mesh prism = scalene_prism();
  const Pose turn =
      moved(Eigen::Vector3d(3, 1, 0)) * turned(Eigen::Vector3d::UnitZ(), 40) * moved(Eigen::Vector3d(-3, -1, 0));
  const SurfaceDeviation ab = surface_deviation(prism, turn, Pose{}, 0.1);
  const SurfaceDeviation ba = surface_deviation(prism, Pose{}, turn, 0.1);
  CHECK(ab.distance > 0.5);
  CHECK(ab.distance == doctest::Approx(ba.distance).epsilon(1e-12));
  CHECK(ab.where_at_a != ba.where_at_a);
  CHECK((ab.where - ba.where).norm() < 1e-12);
}
