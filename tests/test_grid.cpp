// Sample grids (core/grid.h): coverage of the padded box, centring, spacing and
// resolution modes, index/point layout, errors, and the scene-wide common spacing.
#include <cmath>
#include <doctest/doctest.h>
#include <limits>
#include <optional>
#include <vector>

#include "core/grid.h"
#include "snapfit/error.h"

using namespace snapfit;
using Eigen::AlignedBox3d;
using Eigen::Vector3d;

namespace {

GridParams with_spacing(double spacing, double padding) {
  GridParams p;
  p.spacing = spacing;
  p.padding = padding;
  return p;
}

GridParams with_resolution(int resolution, double padding) {
  GridParams p;
  p.resolution = resolution;
  p.padding = padding;
  return p;
}

// Coverage and centring of `grid` on `box` grown by `padding`.
void check_covers(const GridSpec& grid, const AlignedBox3d& box, double padding) {
  const Vector3d lo = box.min().array() - padding, hi = box.max().array() + padding;
  const Vector3d first = grid.point(0, 0, 0);
  const Vector3d last = grid.point(grid.dims.x() - 1, grid.dims.y() - 1, grid.dims.z() - 1);
  const double h = grid.spacing, eps = 1e-9 * (1.0 + hi.cwiseAbs().maxCoeff() + lo.cwiseAbs().maxCoeff());
  for (int a = 0; a < 3; ++a) {
    CAPTURE(a);
    CHECK(grid.dims[a] >= 1);
    CHECK(first[a] <= lo[a] + eps);
    CHECK(last[a] >= hi[a] - eps);
    const double below = lo[a] - first[a], above = last[a] - hi[a];
    CHECK(below >= -eps);
    CHECK(below < h);  // overhang less than one spacing on each side...
    CHECK(above < h);
    CHECK(below + above < h);               // ...and less than one spacing in all
    CHECK(std::abs(below - above) <= eps);  // centred
  }
}

}  // namespace

TEST_CASE("grid: spacing mode covers the padded box, centred") {
  const AlignedBox3d box(Vector3d(-1.3, 0.2, 5.0), Vector3d(2.1, 0.9, 5.05));
  for (double spacing : {0.1, 0.37, 1.0, 3.0}) {
    for (double padding : {0.0, 0.25, 2.0}) {
      CAPTURE(spacing);
      CAPTURE(padding);
      const GridSpec grid = make_grid(box, with_spacing(spacing, padding));
      CHECK(grid.spacing == spacing);
      check_covers(grid, box, padding);
      // The fewest points that cover: one less would not reach across.
      const Vector3d extent = box.sizes().array() + 2 * padding;
      for (int a = 0; a < 3; ++a) CHECK((grid.dims[a] - 2) * spacing < extent[a]);
    }
  }
}

TEST_CASE("grid: an exact fit has no overhang") {
  // Extent 2 + 2 * 0.5 = 3 at spacing 0.5: 7 points, exactly from -0.5 to 2.5.
  const AlignedBox3d box(Vector3d(0, 0, 0), Vector3d(2, 1, 0));
  const GridSpec grid = make_grid(box, with_spacing(0.5, 0.5));
  CHECK(grid.dims == Eigen::Vector3i(7, 5, 3));
  CHECK(grid.origin.x() == doctest::Approx(-0.5).epsilon(1e-12));
  CHECK(grid.origin.y() == doctest::Approx(-0.5).epsilon(1e-12));
  CHECK(grid.origin.z() == doctest::Approx(-0.5).epsilon(1e-12));
  CHECK(grid.point(6, 4, 2).x() == doctest::Approx(2.5).epsilon(1e-12));
  CHECK(grid.point(6, 4, 2).y() == doctest::Approx(1.5).epsilon(1e-12));
  CHECK(grid.point(6, 4, 2).z() == doctest::Approx(0.5).epsilon(1e-12));
  check_covers(grid, box, 0.5);
}

TEST_CASE("grid: flat box without padding gets one point across") {
  const AlignedBox3d box(Vector3d(0, 0, 1), Vector3d(2, 3, 1));
  const GridSpec grid = make_grid(box, with_spacing(0.5, 0.0));
  CHECK(grid.dims == Eigen::Vector3i(5, 7, 1));
  CHECK(grid.origin.z() == doctest::Approx(1.0));
  check_covers(grid, box, 0.0);
}

TEST_CASE("grid: resolution mode puts `resolution` points along the longest padded axis") {
  const AlignedBox3d box(Vector3d(-1, -2, 0.5), Vector3d(3, 1, 1.5));
  for (int resolution : {2, 3, 17, 64, 101}) {
    for (double padding : {0.0, 0.3, 4.0}) {
      CAPTURE(resolution);
      CAPTURE(padding);
      const GridSpec grid = make_grid(box, with_resolution(resolution, padding));
      const Vector3d extent = box.sizes().array() + 2 * padding;
      int longest;
      extent.maxCoeff(&longest);
      CHECK(grid.dims[longest] == resolution);
      CHECK(grid.spacing == doctest::Approx(extent[longest] / (resolution - 1)).epsilon(1e-14));
      for (int a = 0; a < 3; ++a) CHECK(grid.dims[a] <= resolution);
      check_covers(grid, box, padding);
      // The longest axis is an exact fit.
      CHECK(grid.origin[longest] == doctest::Approx(box.min()[longest] - padding).epsilon(1e-12));
    }
  }
  // Spacing wins when both are given.
  GridParams both = with_resolution(10, 0.0);
  both.spacing = 0.5;
  CHECK(make_grid(box, both).spacing == 0.5);
}

TEST_CASE("grid: index and point layout, i fastest") {
  const GridSpec grid = make_grid(AlignedBox3d(Vector3d(0, 0, 0), Vector3d(1.0, 0.6, 0.4)), with_spacing(0.2, 0.1));
  REQUIRE(grid.dims.minCoeff() > 1);
  CHECK(grid.count() == static_cast<std::size_t>(grid.dims.x()) * grid.dims.y() * grid.dims.z());
  std::size_t expected = 0;
  bool in_order = true, points_ok = true;
  for (int k = 0; k < grid.dims.z(); ++k)
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        in_order = in_order && grid.index(i, j, k) == expected++;
        const Vector3d p = grid.point(i, j, k);
        points_ok = points_ok && (p - (grid.origin + grid.spacing * Vector3d(i, j, k))).norm() <= 1e-12;
      }
  CHECK(in_order);
  CHECK(points_ok);
  CHECK(expected == grid.count());
  CHECK(grid.index(1, 0, 0) == 1);
  CHECK(grid.index(0, 1, 0) == static_cast<std::size_t>(grid.dims.x()));
  CHECK(grid.index(0, 0, 1) == static_cast<std::size_t>(grid.dims.x()) * grid.dims.y());
  CHECK(grid.point(0, 0, 0) == grid.origin);
  // Large indices do not overflow int arithmetic.
  GridSpec big;
  big.dims = Eigen::Vector3i(2000, 2000, 1000);
  CHECK(big.count() == 4000000000ull);
  CHECK(big.index(1999, 1999, 999) == 4000000000ull - 1);
}

TEST_CASE("grid: errors") {
  const AlignedBox3d unit(Vector3d(0, 0, 0), Vector3d(1, 1, 1));
  CHECK_THROWS_AS(make_grid(AlignedBox3d(), with_spacing(0.1, 0.0)), Error);  // empty
  CHECK_THROWS_AS(make_grid(AlignedBox3d(Vector3d(0, 0, 0), Vector3d(std::nan(""), 1, 1)), with_spacing(0.1, 0.0)),
                  Error);
  CHECK_THROWS_AS(make_grid(AlignedBox3d(Vector3d(0, 0, 0), Vector3d(std::numeric_limits<double>::infinity(), 1, 1)),
                            with_spacing(0.1, 0.0)),
                  Error);
  GridParams none;
  none.padding = 1.0;
  CHECK_THROWS_WITH_AS(make_grid(unit, none), doctest::Contains("spacing or a resolution"), Error);
  CHECK_THROWS_AS(make_grid(unit, with_spacing(0.0, 0.0)), Error);
  CHECK_THROWS_AS(make_grid(unit, with_spacing(-0.1, 0.0)), Error);
  CHECK_THROWS_AS(make_grid(unit, with_spacing(std::nan(""), 0.0)), Error);
  CHECK_THROWS_AS(make_grid(unit, with_spacing(std::numeric_limits<double>::infinity(), 0.0)), Error);
  // A single point with no padding has no extent to divide.
  CHECK_THROWS_AS(make_grid(AlignedBox3d(Vector3d(1, 1, 1), Vector3d(1, 1, 1)), with_resolution(10, 0.0)), Error);
  // More than 2^31 points: 2001^3 ~ 8e9, and 1291^3 ~ 2.15e9 just over; 1290^3 just under.
  CHECK_THROWS_WITH_AS(make_grid(unit, with_spacing(5e-4, 0.0)), doctest::Contains("2^31"), Error);
  CHECK_THROWS_AS(make_grid(unit, with_spacing(1.0 / 1290, 0.0)), Error);
  const GridSpec under = make_grid(unit, with_spacing(1.0 / 1289, 0.0));
  CHECK(under.dims == Eigen::Vector3i(1290, 1290, 1290));
  CHECK(under.count() < 2147483648ull);
  // Just one axis huge.
  CHECK_THROWS_AS(make_grid(AlignedBox3d(Vector3d(0, 0, 0), Vector3d(1e10, 0, 0)), with_spacing(1.0, 0.0)), Error);
}

TEST_CASE("grid: common_spacing") {
  const std::vector<AlignedBox3d> boxes = {AlignedBox3d(Vector3d(0, 0, 0), Vector3d(2, 1, 1)),
                                           AlignedBox3d(Vector3d(-5, 0, 0), Vector3d(-4, 3.5, 0.5))};
  CHECK(common_spacing(with_spacing(0.3, 10.0), boxes) == 0.3);
  CHECK(common_spacing(with_spacing(0.3, 0.0), {}) == 0.3);
  // Longest padded extent over both boxes: 3.5 + 2 * 0.25 = 4 (the second box's y).
  CHECK(common_spacing(with_resolution(41, 0.25), boxes) == doctest::Approx(4.0 / 40).epsilon(1e-14));
  CHECK(common_spacing(with_resolution(41, 0.25), {boxes[0]}) == doctest::Approx(2.5 / 40).epsilon(1e-14));
  // With that spacing, the box holding the longest extent gets `resolution` points.
  GridParams fixed = with_spacing(common_spacing(with_resolution(41, 0.25), boxes), 0.25);
  CHECK(make_grid(boxes[1], fixed).dims.y() == 41);
  CHECK(make_grid(boxes[0], fixed).dims.maxCoeff() < 41);
  GridParams none;
  CHECK_THROWS_AS(common_spacing(none, boxes), Error);
  CHECK_THROWS_AS(common_spacing(with_resolution(1, 0.0), boxes), Error);
  CHECK_THROWS_AS(common_spacing(with_resolution(0, 0.0), boxes), Error);
}

TEST_CASE("grid: brick_point_order lists every point once, in bricks of neighbours") {
  GridSpec grid;
  grid.dims = Eigen::Vector3i(5, 3, 7);  // odd: bricks of 2 and 4 are cut at the far faces
  for (const int lanes : {1, 4, 8, 16}) {
    CAPTURE(lanes);
    const std::vector<long long> order = brick_point_order(grid, lanes);
    REQUIRE(order.size() % lanes == 0);
    std::vector<int> seen(grid.count(), 0);
    bool packets_compact = true;
    for (std::size_t first = 0; first < order.size(); first += lanes) {
      Eigen::Vector3i lo(1 << 30, 1 << 30, 1 << 30), hi(-1, -1, -1);
      for (int l = 0; l < lanes; ++l) {
        const long long id = order[first + l];
        if (id < 0) continue;
        REQUIRE(id < static_cast<long long>(grid.count()));
        ++seen[static_cast<std::size_t>(id)];
        const Eigen::Vector3i ijk(static_cast<int>(id % 5), static_cast<int>(id / 5 % 3), static_cast<int>(id / 15));
        lo = lo.cwiseMin(ijk);
        hi = hi.cwiseMax(ijk);
      }
      // A packet spans at most its brick: 1x1x1, 2x2x1, 2x2x2 or 4x2x2 points.
      const Eigen::Vector3i extent = hi - lo + Eigen::Vector3i::Ones();
      packets_compact = packets_compact && extent.prod() <= lanes;
    }
    CHECK(packets_compact);
    CHECK(std::count(seen.begin(), seen.end(), 1) == static_cast<long>(grid.count()));
  }
  // One lane is plain grid order.
  const std::vector<long long> plain = brick_point_order(grid, 1);
  for (std::size_t i = 0; i < plain.size(); ++i) REQUIRE(plain[i] == static_cast<long long>(i));
  CHECK_THROWS_WITH_AS(brick_point_order(grid, 3), doctest::Contains("1, 4, 8 or 16"), Error);
}

TEST_CASE("grid: point(index) inverts index(i, j, k)") {
  GridSpec grid;
  grid.origin = {0.5, -1.0, 2.0};
  grid.spacing = 0.25;
  grid.dims = Eigen::Vector3i(5, 3, 7);
  bool ok = true;
  for (int k = 0; k < 7; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 5; ++i) ok = ok && grid.point(grid.index(i, j, k)) == grid.point(i, j, k);
  CHECK(ok);
}

TEST_CASE("grid: sample_trilinear reproduces trilinear functions and is `outside` beyond the grid") {
  GridSpec g;
  g.origin = Vector3d(-1, 2, 0.5);
  g.spacing = 0.25;
  g.dims = Eigen::Vector3i(9, 5, 7);
  // f = a + bx + cy + dz + e xyz is trilinear on every cell, so interpolation is exact.
  auto f = [](const Vector3d& p) { return 1.5 + 2 * p.x() - 3 * p.y() + 0.5 * p.z() + 0.75 * p.x() * p.y() * p.z(); };
  std::vector<float> values(g.count());
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<float>(f(g.point(i)));
  const Vector3d hi = g.point(8, 4, 6);
  for (int n = 0; n < 200; ++n) {
    const Vector3d t(std::fmod(0.6180339 * n, 1.0), std::fmod(0.7548776 * n, 1.0), std::fmod(0.5698403 * n, 1.0));
    const Vector3d p = g.origin + t.cwiseProduct(hi - g.origin);
    CHECK(sample_trilinear(g, values.data(), p, -7) == doctest::Approx(f(p)).epsilon(1e-5));
  }
  CHECK(sample_trilinear(g, values.data(), hi, -7) == doctest::Approx(f(hi)).epsilon(1e-6));  // the far corner
  CHECK(sample_trilinear(g, values.data(), g.origin - Vector3d(1e-9, 0, 0), -7) == -7);
  CHECK(sample_trilinear(g, values.data(), hi + Vector3d(0, 0, 1e-9), -7) == -7);
  CHECK(sample_trilinear(g, values.data(), Vector3d(std::nan(""), 2, 1), -7) == -7);
  // One point along an axis: exact on its plane.
  GridSpec flat = g;
  flat.dims = Eigen::Vector3i(9, 5, 1);
  CHECK(sample_trilinear(flat, values.data(), Vector3d(0, 2.5, 0.5), -7) ==
        doctest::Approx(f({0, 2.5, 0.5})).epsilon(1e-5));
  CHECK(sample_trilinear(flat, values.data(), Vector3d(0, 2.5, 0.6), -7) == -7);
}
