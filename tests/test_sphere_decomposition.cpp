// Spherical decomposition (engine/fields/sphere_decomposition.h, seed 001 Algorithm 1) and its
// error estimate (engine/fields/ball_union_error.h), against closed forms: a box and a cylinder
// (distances and volumes known), a cube with its inscribed and circumscribed balls
// (symmetric differences known), and the shipped peg-in-hole block.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>

#include "engine/fields/ball_union_error.h"
#include "engine/fields/sphere_decomposition.h"
#include "mesh/procedural/procedural_parts.h"
#include "snapfit/scene.h"
#include "tests/test_engine_support.h"
#include "tests/test_meshes.h"

using namespace snapfit;

namespace {

// The box [-a, a] x [-b, b] x [-c, c], outward-wound.
Mesh box_mesh(double a, double b, double c) {
  Mesh m;
  for (int k = 0; k < 8; ++k) m.vertices.push_back({k & 1 ? a : -a, k & 2 ? b : -b, k & 4 ? c : -c});
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    m.triangles.push_back({q[0], q[1], q[2]});
    m.triangles.push_back({q[0], q[2], q[3]});
  }
  return m;
}

DescriptorOptions quiet_options() {
  DescriptorOptions o;
  o.program_cache = test::test_program_cache();
  return o;
}

SphereDecomposition decompose(const Mesh& mesh, double tolerance, double protrusion = 0.25) {
  SphereDecompositionParams p;
  p.tolerance = tolerance;
  p.protrusion = protrusion;
  return decompose_part(test::test_context(), mesh, DescriptorParams{}, p, quiet_options());
}

// Every grid node of `grid` for which `inside` holds lies in the union of `balls`.
template <class Inside>
std::size_t uncovered_nodes(const GridSpec& grid, const std::vector<Ball>& balls, Inside inside) {
  std::vector<Eigen::Vector3d> nodes;
  for (std::size_t id = 0; id < grid.count(); ++id)
    if (inside(grid.point(id))) nodes.push_back(grid.point(id));
  const std::vector<char> in = inside_ball_union(balls, nodes);
  return static_cast<std::size_t>(std::count(in.begin(), in.end(), 0));
}

// Steiner: the volume of box (+) B(0, e) minus the box's.
double box_shell_volume(double a, double b, double c, double e) {
  const double pi = 3.14159265358979323846;
  return 8 * (a * b + b * c + c * a) * e + 2 * pi * (a + b + c) * e * e + 4.0 / 3.0 * pi * e * e * e;
}

}  // namespace

TEST_CASE("ball union error: a cube against its inscribed and circumscribed balls (closed forms)") {
  const double pi = 3.14159265358979323846;
  const Mesh cube = box_mesh(1, 1, 1);
  const struct {
    double radius, truth;
  } cases[] = {{1.0, 8.0 - 4.0 / 3.0 * pi}, {std::sqrt(3.0), 4.0 * pi * std::sqrt(3.0) - 8.0}};
  for (const auto& c : cases) {
    CAPTURE(c.radius);
    const BallUnionError e =
        ball_union_error(test::test_context(), cube, {{Eigen::Vector3d::Zero(), c.radius}}, 100000, 7, quiet_options());
    CHECK(e.solid_volume == doctest::Approx(8.0).epsilon(1e-12));
    CHECK(e.volume_error_low <= c.truth);
    CHECK(e.volume_error_high >= c.truth);
    CHECK(e.volume_error_high - e.volume_error_low < 0.03 * c.truth);
    // d_H = sqrt(3) - 1 in both cases (a corner to the inscribed ball, the circumscribed
    // ball's pole to a face); the samples near the extreme points come within 0.1 of it.
    CHECK(e.hausdorff_sampled <= std::sqrt(3.0) - 1.0 + 1e-5);
    CHECK(e.hausdorff_sampled >= std::sqrt(3.0) - 1.1);
  }
}

TEST_CASE(
    "spherical decomposition of a box: radii are the closed-form distances, the union covers, errors within "
    "epsilon") {
  const double a = 2, b = 1.5, c = 1;
  const Mesh box = box_mesh(a, b, c);
  auto box_distance = [&](const Eigen::Vector3d& p) {
    return std::min({a - std::abs(p.x()), b - std::abs(p.y()), c - std::abs(p.z())});
  };
  double previous_error = 1e300;
  for (double tolerance : {0.3, 0.15}) {
    CAPTURE(tolerance);
    const SphereDecomposition d = decompose(box, tolerance);
    CHECK(d.epsilon == tolerance);
    CHECK(d.spacing == doctest::Approx(2 * tolerance / std::sqrt(3.0)));
    REQUIRE(!d.balls.empty());
    CHECK(d.balls.size() < d.sampled_balls);  // the reduction (A.4) drops engulfed balls
    CHECK(d.sampled_balls < d.inside_nodes);
    for (const Ball& ball : d.balls) {
      REQUIRE(box_distance(ball.centre) > 0);
      CHECK(ball.radius - d.epsilon == doctest::Approx(box_distance(ball.centre)).epsilon(1e-4));
    }
    // Proposition 3's proof needs S(A1) in S(A3): every node inside is covered.
    const GridSpec grid = sphere_grid(box, tolerance);
    CHECK(uncovered_nodes(grid, d.balls, [&](const Eigen::Vector3d& p) { return box_distance(p) > 1e-6; }) == 0);
    const BallUnionError e = ball_union_error(test::test_context(), box, d.balls, 100000, 3, quiet_options());
    CHECK(e.solid_volume == doctest::Approx(8 * a * b * c).epsilon(1e-12));
    CHECK(e.hausdorff_sampled <= d.epsilon * (1 + 1e-4));
    CHECK(e.volume_error_high <= box_shell_volume(a, b, c, d.epsilon));
    CHECK(e.volume_error < previous_error);
    previous_error = e.volume_error;
  }
}

TEST_CASE("spherical decomposition of a cylinder: radii, covering and volume error") {
  const double radius = 1, length = 3;
  const Mesh peg = test::peg_mesh(radius, length);  // z in [0, length]
  const double inradius = radius * std::cos(3.14159265358979323846 / 64);
  auto distance = [&](const Eigen::Vector3d& p) {
    return std::min({inradius - std::hypot(p.x(), p.y()), p.z(), length - p.z()});
  };
  const SphereDecomposition d = decompose(peg, 0.12);
  REQUIRE(!d.balls.empty());
  for (const Ball& ball : d.balls)
    CHECK(ball.radius - d.epsilon == doctest::Approx(distance(ball.centre)).epsilon(2e-3 * radius));
  CHECK(uncovered_nodes(sphere_grid(peg, 0.12), d.balls,
                        [&](const Eigen::Vector3d& p) { return distance(p) > 1e-6; }) == 0);
  const BallUnionError e = ball_union_error(test::test_context(), peg, d.balls, 100000, 5, quiet_options());
  CHECK(e.hausdorff_sampled <= d.epsilon * (1 + 1e-4));
  // The union lies within epsilon of the cylinder; Steiner bounds that shell's volume.
  const double pi = 3.14159265358979323846, eps = d.epsilon;
  const double shell = 2 * pi * radius * length * eps + 2 * pi * radius * radius * eps + pi * pi * radius * eps * eps +
                       pi * length * eps * eps + 4.0 / 3.0 * pi * eps * eps * eps;
  CHECK(e.volume_error_high <= shell);
  CHECK(e.volume_error < 0.25 * e.solid_volume);
}

TEST_CASE("spherical decomposition of the shipped hole block: fewer balls than nodes, errors shrink with epsilon") {
  const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  const Mesh block = make_procedural_part(*scene.part1.procedural);
  double previous_error = 1e300;
  std::size_t previous_balls = 0;
  for (double tolerance : {2.5, 1.6}) {
    CAPTURE(tolerance);
    const SphereDecomposition d = decompose(block, tolerance);
    CHECK(d.balls.size() > previous_balls);
    CHECK(d.balls.size() < d.sampled_balls);  // the reduction drops engulfed balls
    CHECK(d.sampled_balls < d.inside_nodes);  // a ball covers more than its own node
    const BallUnionError e = ball_union_error(test::test_context(), block, d.balls, 100000, 11, quiet_options());
    CHECK(e.hausdorff_sampled <= d.epsilon * (1 + 1e-4));
    CHECK(e.volume_error < previous_error);
    previous_error = e.volume_error;
    previous_balls = d.balls.size();
  }
}

TEST_CASE("spherical decomposition: bad input gives a clear error") {
  const Mesh box = box_mesh(1, 1, 1);
  CHECK(test::error_of([&] { decompose(box, -1); }).find("tolerance must be a positive number") != std::string::npos);
  CHECK(test::error_of([&] { decompose(box, std::nan("")); }).find("tolerance") != std::string::npos);
  CHECK(test::error_of([&] { decompose(box, 0.2, 1.5); }).find("protrusion must be in [0, 1]") != std::string::npos);
  CHECK(test::error_of([&] { decompose(Mesh{}, 0.2); }).find("mesh is empty") != std::string::npos);
  CHECK(test::error_of([&] { ball_union_error(test::test_context(), box, {}, 10); }).find("no balls") !=
        std::string::npos);
  const GridSpec g = sphere_grid(box, 0.5);
  const std::vector<float> zeros(g.count(), 0.0f);
  CHECK(test::error_of([&] { decompose_into_balls(g, zeros, zeros, zeros, 0.5, 0.25); }).find("no grid node") !=
        std::string::npos);
  CHECK(test::error_of([&] { decompose_into_balls(g, {}, zeros, zeros, 0.5, 0.25); }).find("do not match") !=
        std::string::npos);
}
