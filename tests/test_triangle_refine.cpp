// Triangle refinement (mesh/triangle_refine.h): pieces fit the radius, and the
// surface integrals (area, area vector, enclosed volume) and orientation are unchanged;
// a coarse radius is a no-op; the piece limit and bad radii throw.
#include <cmath>
#include <doctest/doctest.h>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "mesh/procedural/procedural_parts.h"
#include "mesh/triangle_refine.h"
#include "snapfit/error.h"
#include "tests/test_meshes.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

Mesh refine_soup(int n, unsigned seed) { return test::random_soup(n, seed, 2.0, 0.8); }

// A long thin (needle) triangle and a zero-area one with a long edge.
Mesh awkward_triangles() {
  Mesh m;
  m.vertices = {Vector3d(0, 0, 0), Vector3d(10, 0, 0), Vector3d(5, 0.01, 0.002),
                Vector3d(0, 1, 0), Vector3d(4, 1, 0),  Vector3d(8, 1, 0)};
  m.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(3, 4, 5)};
  return m;
}

Mesh one_triangle(const Mesh& mesh, std::size_t t) {
  Mesh m;
  for (int k = 0; k < 3; ++k) m.vertices.push_back(mesh.vertices[mesh.triangles[t][k]]);
  m.triangles = {Eigen::Vector3i(0, 1, 2)};
  return m;
}

Vector3d area_vector(const Vector3d& a, const Vector3d& b, const Vector3d& c) { return 0.5 * (b - a).cross(c - a); }

double centroid_radius(const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d m = (a + b + c) / 3.0;
  return std::max({(a - m).norm(), (b - m).norm(), (c - m).norm()});
}

struct Integrals {
  double area = 0, volume = 0, max_radius = 0;
  Vector3d area_vector = Vector3d::Zero();
};

Integrals integrals(const Mesh& m) {
  Integrals s;
  for (const auto& t : m.triangles) {
    const Vector3d &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const Vector3d an = area_vector(a, b, c);
    s.area += an.norm();
    s.area_vector += an;
    s.volume += a.dot(b.cross(c)) / 6.0;
    s.max_radius = std::max(s.max_radius, centroid_radius(a, b, c));
  }
  return s;
}

bool indices_valid(const Mesh& m) {
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      if (t[k] < 0 || t[k] >= static_cast<int>(m.vertices.size())) return false;
  return true;
}

// Every piece fits the radius, and the totals match the input.
void check_refined(const Mesh& mesh, const Mesh& refined, double max_radius) {
  REQUIRE(indices_valid(refined));
  CHECK(refined.triangles.size() >= mesh.triangles.size());
  const Integrals before = integrals(mesh), after = integrals(refined);
  CHECK(after.max_radius <= max_radius * (1 + 1e-12));
  CHECK(after.area == doctest::Approx(before.area).epsilon(1e-12));
  CHECK((after.area_vector - before.area_vector).norm() <= 1e-12 * before.area);
  CHECK(std::abs(after.volume - before.volume) <= 1e-12 * std::max(std::abs(before.volume), before.area * 1.0));
}

// Refines each triangle alone: pieces lie in their parent (barycentric coordinates in
// [0, 1]) and keep its orientation; the whole-mesh refinement has the same piece count.
void check_orientation(const Mesh& mesh, double max_radius) {
  std::size_t total = 0;
  double disagreeing_area = 0, parent_area = 0, piece_area = 0;
  bool inside = true;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Mesh parent = one_triangle(mesh, t);
    const Mesh pieces = refine_triangles(parent, max_radius);
    total += pieces.triangles.size();
    const Vector3d &a = parent.vertices[0], &b = parent.vertices[1], &c = parent.vertices[2];
    const Vector3d n = area_vector(a, b, c);
    parent_area += n.norm();
    if (n.norm() == 0) continue;
    for (const auto& p : pieces.triangles) {
      const Vector3d &pa = pieces.vertices[p[0]], &pb = pieces.vertices[p[1]], &pc = pieces.vertices[p[2]];
      const Vector3d pn = area_vector(pa, pb, pc);
      piece_area += pn.norm();
      if (pn.dot(n) <= 0 && pn.norm() > 0) disagreeing_area += pn.norm();
      for (const Vector3d* v : {&pa, &pb, &pc}) {
        // Barycentric coordinates of v in (a, b, c) and its distance from the plane.
        const Vector3d q = *v - a;
        const double nn = n.squaredNorm() * 4.0;  // |(b - a) x (c - a)|^2
        const double beta = (q.cross(c - a)).dot(2.0 * n) / nn;
        const double gamma = ((b - a).cross(q)).dot(2.0 * n) / nn;
        const double off_plane = std::abs(q.dot(n.normalized()));
        const double eps = 1e-9;
        if (beta < -eps || gamma < -eps || beta + gamma > 1 + eps || off_plane > 1e-9 * (1 + a.norm())) inside = false;
      }
    }
  }
  CHECK(disagreeing_area == 0.0);
  CHECK(inside);
  CHECK(piece_area == doctest::Approx(parent_area).epsilon(1e-12));
  CHECK(refine_triangles(mesh, max_radius).triangles.size() == total);
}

}  // namespace

TEST_CASE("refine: peg pieces fit the radius, integrals and orientation are kept") {
  const Mesh mesh = test::peg_mesh(1, 3);
  const Integrals before = integrals(mesh);
  REQUIRE(before.volume > 0);
  for (double radius : {0.5, 0.2, 0.05}) {
    CAPTURE(radius);
    const Mesh refined = refine_triangles(mesh, radius);
    check_refined(mesh, refined, radius);
    CHECK(refined.triangles.size() > mesh.triangles.size());
    // Closed mesh: the enclosed volume (divergence theorem, sum det / 6) is unchanged
    // even though the refined soup is not welded.
    CHECK(integrals(refined).volume == doctest::Approx(before.volume).epsilon(1e-12));
    check_orientation(mesh, radius);
  }
  // Volume is translation invariant for a closed surface: move the peg and refine again.
  Mesh moved = mesh;
  for (Vector3d& v : moved.vertices) v += Vector3d(3.5, -2.0, 7.25);
  CHECK(integrals(refine_triangles(moved, 0.1)).volume == doctest::Approx(before.volume).epsilon(1e-11));
}

TEST_CASE("refine: random soup and awkward triangles") {
  const Mesh soup = refine_soup(200, 3u);
  for (double radius : {1.0, 0.3, 0.07}) {
    CAPTURE(radius);
    check_refined(soup, refine_triangles(soup, radius), radius);
    check_orientation(soup, radius);
  }
  const Mesh awkward = awkward_triangles();
  for (double radius : {1.0, 0.01}) {
    CAPTURE(radius);
    const Mesh refined = refine_triangles(awkward, radius);
    check_refined(awkward, refined, radius);
    check_orientation(awkward, radius);
  }
}

TEST_CASE("refine: a radius larger than every triangle changes nothing") {
  for (const Mesh& mesh : {test::peg_mesh(1, 3), refine_soup(50, 11u), awkward_triangles()}) {
    const double largest = integrals(mesh).max_radius;
    const Mesh same = refine_triangles(mesh, largest * 1.001);
    REQUIRE(same.triangles.size() == mesh.triangles.size());
    bool identical = true;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        identical = identical && same.vertices[same.triangles[t][k]] == mesh.vertices[mesh.triangles[t][k]];
    CHECK(identical);
    CHECK(refine_triangles(mesh, 1e6).triangles.size() == mesh.triangles.size());
  }
  CHECK(refine_triangles(Mesh{}, 0.1).triangles.empty());
}

TEST_CASE("refine: the piece limit throws a clear error") {
  const Mesh mesh = test::peg_mesh(1, 3);
  const std::size_t pieces = refine_triangles(mesh, 0.1).triangles.size();
  REQUIRE(pieces > mesh.triangles.size());
  CHECK(refine_triangles(mesh, 0.1, pieces).triangles.size() == pieces);  // exactly at the limit is fine
  try {
    refine_triangles(mesh, 0.1, pieces - 1);
    FAIL("expected snapfit::Error");
  } catch (const Error& e) {
    const std::string what = e.what();
    CHECK(what.find(std::to_string(pieces)) != std::string::npos);      // how many it would give
    CHECK(what.find(std::to_string(pieces - 1)) != std::string::npos);  // the limit
    CHECK(what.find("more than") != std::string::npos);
  }
  CHECK_THROWS_AS(refine_triangles(mesh, 0.01, 1000), Error);
}

TEST_CASE("refine: non-positive or non-finite radius throws") {
  const Mesh mesh = test::peg_mesh(1, 3);
  CHECK_THROWS_AS(refine_triangles(mesh, 0.0), Error);
  CHECK_THROWS_AS(refine_triangles(mesh, -1.0), Error);
  CHECK_THROWS_AS(refine_triangles(mesh, std::nan("")), Error);
  CHECK_THROWS_AS(refine_triangles(mesh, std::numeric_limits<double>::infinity()), Error);
  CHECK_THROWS_WITH_AS(refine_triangles(mesh, -1.0), doctest::Contains("radius"), Error);
}
