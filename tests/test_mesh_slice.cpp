// A mesh cut by an axis-aligned plane (mesh/mesh_slice.h), against closed forms.
#include <cmath>
#include <doctest/doctest.h>

#include "mesh/mesh_slice.h"
#include "snapfit/error.h"
#include "tests/test_meshes.h"

using namespace snapfit;

TEST_CASE("mesh slice: the peg cut along its axis is a rectangle, across it a 64-gon") {
  const double r = 5, length = 30;
  const Mesh peg = test::peg_mesh(r, length);  // along +z from z = 0, vertices at angles 2 pi i / 64

  // y = 0 holds two of the polygon's vertices (angles 0 and pi): the outline is the
  // rectangle [-r, r] x [0, length], perimeter 2 (2r + length).
  const std::vector<OutlineSegment> side = mesh_slice_outline(peg, 'y', 0.0);
  REQUIRE_FALSE(side.empty());
  double perimeter = 0;
  for (const OutlineSegment& s : side) {
    perimeter += (s.b - s.a).norm();
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      const bool on_side = std::abs(std::abs(p.x()) - r) < 1e-9;
      const bool on_cap = std::abs(p.y()) < 1e-9 || std::abs(p.y() - length) < 1e-9;
      CHECK((on_side || on_cap));
      CHECK(std::abs(p.x()) <= r + 1e-9);
    }
  }
  CHECK(perimeter == doctest::Approx(2 * (2 * r + length)).epsilon(1e-9));

  // z = 12: the regular 64-gon of circumradius r, perimeter 64 * 2 r sin(pi / 64), in (x, y).
  const std::vector<OutlineSegment> ring = mesh_slice_outline(peg, 'z', 12.0);
  perimeter = 0;
  for (const OutlineSegment& s : ring) {
    perimeter += (s.b - s.a).norm();
    // On the polygon: between its inscribed and circumscribed circles.
    for (const Eigen::Vector2d& p : {s.a, s.b}) {
      CHECK(p.norm() <= r + 1e-9);
      CHECK(p.norm() >= r * std::cos(M_PI / 64) - 1e-9);
    }
  }
  CHECK(ring.size() >= 64);
  CHECK(perimeter == doctest::Approx(64 * 2 * r * std::sin(M_PI / 64)).epsilon(1e-9));

  // x = 2: the (u, v) = (y, z) plane; a rectangle of half-width sqrt(r^2 - 4) up to the
  // polygon's flattening, so between the inscribed and circumscribed circles' chords.
  double max_y = 0;
  for (const OutlineSegment& s : mesh_slice_outline(peg, 'x', 2.0))
    for (const Eigen::Vector2d& p : {s.a, s.b}) max_y = std::max(max_y, std::abs(p.x()));
  const double inner = r * std::cos(M_PI / 64);
  CHECK(max_y <= std::sqrt(r * r - 4) + 1e-9);
  CHECK(max_y >= std::sqrt(inner * inner - 4) - 1e-9);

  CHECK(mesh_slice_outline(peg, 'z', 31.0).empty());  // above the peg
  CHECK(mesh_slice_outline(peg, 'z', -1.0).empty());
  CHECK_THROWS_AS(mesh_slice_outline(peg, 'w', 0.0), Error);
}
