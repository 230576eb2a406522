// Triangle hierarchy (engine/fields/triangle_bvh.h): every triangle once, depth-first layout,
// leaf ranges, node bounds and moments recomputed in double from each node's own
// triangles, depth, errors, and the first-order far-field expansion against exact
// solid angles within the remainder bound kernels/winding_number.cl documents.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <doctest/doctest.h>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "engine/fields/triangle_bvh.h"
#include "mesh/procedural/procedural_parts.h"
#include "snapfit/error.h"
#include "tests/test_meshes.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

Mesh bvh_soup(int n, unsigned seed) { return test::random_soup(n, seed, 1.0, 0.3); }

Mesh single_triangle() {
  Mesh m;
  m.vertices = {Vector3d(0.5, -1, 2), Vector3d(2, 0.25, 2.5), Vector3d(-0.5, 1.5, 1)};
  m.triangles = {Eigen::Vector3i(0, 1, 2)};
  return m;
}

// A closed tetrahedron plus two zero-area triangles (collinear, and all three corners
// at one point), which must be kept but contribute nothing.
Mesh with_degenerate_triangles() {
  Mesh m;
  m.vertices = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0), Vector3d(0, 0, 1),
                Vector3d(2, 2, 2), Vector3d(3, 3, 3), Vector3d(4, 4, 4)};
  m.triangles = {Eigen::Vector3i(0, 2, 1), Eigen::Vector3i(0, 1, 3), Eigen::Vector3i(0, 3, 2),
                 Eigen::Vector3i(1, 2, 3), Eigen::Vector3i(4, 5, 6), Eigen::Vector3i(5, 5, 5)};
  return m;
}

using FloatTriangle = std::array<float, 9>;

std::vector<FloatTriangle> mesh_triangles_as_float(const Mesh& m) {
  std::vector<FloatTriangle> out;
  for (const auto& t : m.triangles) {
    FloatTriangle f;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) f[3 * k + a] = static_cast<float>(m.vertices[t[k]][a]);
    out.push_back(f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<FloatTriangle> bvh_triangles(const TriangleBvh& bvh) {
  std::vector<FloatTriangle> out;
  for (std::size_t t = 0; 3 * t < bvh.triangles.size(); ++t) {
    FloatTriangle f;
    for (int k = 0; k < 3; ++k)
      for (int a = 0; a < 3; ++a) f[3 * k + a] = bvh.triangles[3 * t + k].s[a];
    out.push_back(f);
  }
  std::sort(out.begin(), out.end());
  return out;
}

Vector3d v3(const cl_float4& f) { return Vector3d(f.s[0], f.s[1], f.s[2]); }

Vector3d corner(const TriangleBvh& bvh, int t, int k) { return v3(bvh.triangles[3 * t + k]); }

// Node count of median splits (floor half to the left) down to leaf_size.
int expected_node_count(int n, int leaf_size) {
  if (n <= leaf_size) return 1;
  return 1 + expected_node_count(n / 2, leaf_size) + expected_node_count(n - n / 2, leaf_size);
}

// Moments of triangles [first, first + count) in double.
struct Moments {
  double area = 0, abs_moment = 0;
  double second = 0;  // integral of |q - about|^2 dA (edge-midpoint rule, exact for quadratics)
  Vector3d centroid = Vector3d::Zero(), area_normal = Vector3d::Zero();
  Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
};

Moments moments_of(const TriangleBvh& bvh, int first, int count, const Vector3d& about) {
  Moments m;
  Vector3d weighted = Vector3d::Zero();
  for (int t = first; t < first + count; ++t) {
    const Vector3d a = corner(bvh, t, 0), b = corner(bvh, t, 1), c = corner(bvh, t, 2);
    const Vector3d an = 0.5 * (b - a).cross(c - a);
    const Vector3d ct = (a + b + c) / 3.0;
    m.area += an.norm();
    m.area_normal += an;
    weighted += an.norm() * ct;
    m.moment += an * (ct - about).transpose();
    m.abs_moment += an.norm() * (ct - about).norm();
    for (const Vector3d& mid : {Vector3d((a + b) / 2), Vector3d((b + c) / 2), Vector3d((c + a) / 2)})
      m.second += an.norm() / 3.0 * (mid - about).squaredNorm();
  }
  m.centroid = m.area > 0 ? Vector3d(weighted / m.area) : Vector3d::Zero();
  return m;
}

// Checks every structural and per-node property of `bvh`, built over `mesh`.
void check_bvh(const Mesh& mesh, const TriangleBvh& bvh, int leaf_size) {
  const int n = static_cast<int>(mesh.triangles.size());
  REQUIRE(bvh.triangles.size() == 3 * static_cast<std::size_t>(n));
  CHECK(bvh_triangles(bvh) == mesh_triangles_as_float(mesh));

  REQUIRE(!bvh.nodes.empty());
  CHECK(static_cast<int>(bvh.nodes.size()) == expected_node_count(n, leaf_size));

  // Walk from the root: each node once, subtree of node i is [i, i + size), leaf ranges
  // in order partition [0, n).
  std::vector<int> visits(bvh.nodes.size(), 0);
  int next_leaf_first = 0, max_level = 0, leaves = 0;
  std::function<int(int, int, int, int)> walk = [&](int index, int first, int count, int level) -> int {
    REQUIRE(index >= 0);
    REQUIRE(index < static_cast<int>(bvh.nodes.size()));
    ++visits[index];
    max_level = std::max(max_level, level);
    const BvhNode& node = bvh.nodes[index];
    CHECK(node.links.s[1] == first);
    CHECK(node.links.s[2] == count);
    if (node.links.s[0] < 0) {
      ++leaves;
      CHECK(count >= 1);
      CHECK(count <= leaf_size);
      CHECK(first == next_leaf_first);
      next_leaf_first = first + count;
      return 1;
    }
    CHECK(count > leaf_size);
    const int left = index + 1, right = node.links.s[0];
    REQUIRE(right > left);
    REQUIRE(right < static_cast<int>(bvh.nodes.size()));
    const int left_count = bvh.nodes[left].links.s[2];
    CHECK(left_count >= 1);
    CHECK(left_count < count);
    const int left_size = walk(left, first, left_count, level + 1);
    CHECK(right == left + left_size);  // depth-first: right subtree follows the left one
    const int right_size = walk(right, first + left_count, count - left_count, level + 1);
    return 1 + left_size + right_size;
  };
  const int size = walk(0, 0, n, 1);
  CHECK(size == static_cast<int>(bvh.nodes.size()));
  CHECK(next_leaf_first == n);
  CHECK(std::all_of(visits.begin(), visits.end(), [](int v) { return v == 1; }));
  CHECK(bvh.depth == max_level);
  CHECK(bvh.depth <= 2.0 * std::log2(static_cast<double>(n)) + 2.0);
  CHECK(leaves >= (n + leaf_size - 1) / leaf_size);

  // Per-node bounds and moments.
  for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNode& node = bvh.nodes[i];
    const int first = node.links.s[1], count = node.links.s[2];
    const Vector3d lo = v3(node.bbox_min), hi = v3(node.bbox_max), c = v3(node.centroid);
    const double area = node.bbox_min.s[3], radius = node.bbox_max.s[3];
    const Moments m = moments_of(bvh, first, count, c);
    double extent = 0;
    for (int t = first; t < first + count; ++t)
      for (int k = 0; k < 3; ++k) {
        const Vector3d v = corner(bvh, t, k);
        CHECK((v.array() >= lo.array()).all());
        CHECK((v.array() <= hi.array()).all());
        CHECK((v - c).norm() <= radius);
        extent = std::max(extent, (v - c).norm());
      }
    // Tight, not just large: the stored ball exceeds the farthest vertex by at most its
    // documented float margin (8 float steps at the node's coordinate magnitude).
    const double magnitude = std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff());
    CHECK(radius <= extent * (1 + 1e-5) + 8.0 * 1.2e-7 * magnitude * (1 + 1e-5) + 1e-12);
    // Triangles and centre are stored in float: positions carry ~1e-7 relative rounding.
    const double position_tolerance = 1e-6 * (c.norm() + radius);
    CHECK(area == doctest::Approx(m.area).epsilon(1e-5));
    CHECK((v3(node.area_normal) - m.area_normal).norm() <= 1e-5 * m.area);
    if (m.area > 0) CHECK((c - m.centroid).norm() <= 1e-5 * radius + position_tolerance);
    Eigen::Matrix3d stored;
    for (int row = 0; row < 3; ++row) stored.row(row) = v3(node.moment[row]).transpose();
    CHECK((stored - m.moment).norm() <= 1e-5 * m.abs_moment + 4.0 * m.area * position_tolerance);
    // Second moment about the centroid (centroid.w): at least the exact integral, at
    // most its documented float margin above it, and never above r^2 A.
    const double second = node.centroid.s[3];
    CHECK(second >= m.second * (1 - 1e-5) - 1e-12);
    CHECK(second <= m.second * (1 + 1e-4) + 4.0 * radius * m.area * position_tolerance + 1e-12);
    CHECK(second <= radius * radius * area * (1 + 1e-5) + 1e-12);
  }
  CHECK(bvh.nodes[0].bbox_min.s[3] == doctest::Approx(bvh.total_area).epsilon(1e-6));
  CHECK(bvh.total_area == doctest::Approx(moments_of(bvh, 0, n, Vector3d::Zero()).area).epsilon(1e-6));
}

// Signed solid angle of (a, b, c) seen from p, in double (Van Oosterom & Strackee):
// positive when p is behind the counter-clockwise face.
double solid_angle(const Vector3d& p, const Vector3d& va, const Vector3d& vb, const Vector3d& vc) {
  const Vector3d a = va - p, b = vb - p, c = vc - p;
  const double la = a.norm(), lb = b.norm(), lc = c.norm();
  const double det = a.dot(b.cross(c));
  const double div = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0 * std::atan2(det, div);
}

}  // namespace

TEST_CASE("bvh: procedural peg, every leaf size") {
  const Mesh mesh = test::peg_mesh(1, 3);
  REQUIRE(mesh.triangles.size() > 8);
  for (int leaf_size : {1, 2, 4, 7}) {
    CAPTURE(leaf_size);
    const TriangleBvh bvh = build_triangle_bvh(mesh, leaf_size);
    check_bvh(mesh, bvh, leaf_size);
  }
  // A closed mesh: the root's area vector vanishes and its moment is volume * I.
  const TriangleBvh bvh = build_triangle_bvh(mesh);
  const BvhNode& root = bvh.nodes[0];
  CHECK(v3(root.area_normal).norm() <= 1e-5 * bvh.total_area);
  double volume = 0;
  for (const auto& t : mesh.triangles)
    volume += mesh.vertices[t[0]].dot(mesh.vertices[t[1]].cross(mesh.vertices[t[2]])) / 6.0;
  CHECK(volume > 0);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col)
      CHECK(root.moment[row].s[col] == doctest::Approx(row == col ? volume : 0.0).epsilon(1e-5).scale(volume));
}

TEST_CASE("bvh: random triangle soup") {
  for (int n : {2, 5, 100, 1001}) {
    CAPTURE(n);
    const Mesh mesh = bvh_soup(n, 17u + static_cast<unsigned>(n));
    check_bvh(mesh, build_triangle_bvh(mesh), 4);
    check_bvh(mesh, build_triangle_bvh(mesh, 1), 1);
  }
}

TEST_CASE("bvh: large soup takes the parallel build path and is deterministic") {
  // More than 20000 triangles per node spawns TBB tasks for the top levels.
  const Mesh mesh = bvh_soup(50000, 5u);
  const TriangleBvh a = build_triangle_bvh(mesh);
  check_bvh(mesh, a, 4);
  const TriangleBvh b = build_triangle_bvh(mesh);
  REQUIRE(a.nodes.size() == b.nodes.size());
  CHECK(a.depth == b.depth);
  bool same = true;
  for (std::size_t i = 0; i < a.triangles.size(); ++i)
    for (int k = 0; k < 4; ++k) same = same && a.triangles[i].s[k] == b.triangles[i].s[k];
  CHECK(same);
}

TEST_CASE("bvh: single triangle is one leaf") {
  const Mesh mesh = single_triangle();
  const TriangleBvh bvh = build_triangle_bvh(mesh);
  check_bvh(mesh, bvh, 4);
  REQUIRE(bvh.nodes.size() == 1);
  CHECK(bvh.depth == 1);
  CHECK(bvh.nodes[0].links.s[0] == -1);
  CHECK(bvh.nodes[0].links.s[1] == 0);
  CHECK(bvh.nodes[0].links.s[2] == 1);
  const Vector3d an = 0.5 * (mesh.vertices[1] - mesh.vertices[0]).cross(mesh.vertices[2] - mesh.vertices[0]);
  CHECK(bvh.total_area == doctest::Approx(an.norm()).epsilon(1e-12));
  CHECK((v3(bvh.nodes[0].area_normal) - an).norm() <= 1e-6 * an.norm());
  const Vector3d c = (mesh.vertices[0] + mesh.vertices[1] + mesh.vertices[2]) / 3.0;
  CHECK((v3(bvh.nodes[0].centroid) - c).norm() <= 1e-6);
  // One triangle has no first moment about its own centroid.
  for (int row = 0; row < 3; ++row) CHECK(v3(bvh.nodes[0].moment[row]).norm() <= 1e-6);
}

TEST_CASE("bvh: zero-area triangles are kept and contribute nothing") {
  const Mesh mesh = with_degenerate_triangles();
  for (int leaf_size : {1, 2, 4}) {
    CAPTURE(leaf_size);
    const TriangleBvh bvh = build_triangle_bvh(mesh, leaf_size);
    check_bvh(mesh, bvh, leaf_size);
    // Tetrahedron area: three right triangles of 1/2 and an equilateral one of side sqrt 2.
    CHECK(bvh.total_area == doctest::Approx(1.5 + std::sqrt(3.0) / 2.0).epsilon(1e-12));
    CHECK(v3(bvh.nodes[0].area_normal).norm() <= 1e-6);
    // Leaves holding only degenerate triangles have zero area and a finite centre.
    for (const BvhNode& node : bvh.nodes) {
      CHECK(std::isfinite(node.centroid.s[0]));
      CHECK(std::isfinite(node.bbox_max.s[3]));
      CHECK(node.bbox_min.s[3] >= 0.0f);
    }
  }
  // Only degenerate triangles at all.
  Mesh flat;
  flat.vertices = {Vector3d(0, 0, 0), Vector3d(1, 1, 1), Vector3d(2, 2, 2)};
  flat.triangles = {Eigen::Vector3i(0, 1, 2), Eigen::Vector3i(1, 1, 1)};
  const TriangleBvh bvh = build_triangle_bvh(flat);
  check_bvh(flat, bvh, 4);
  CHECK(bvh.total_area == 0.0);
}

TEST_CASE("bvh: errors") {
  CHECK_THROWS_AS(build_triangle_bvh(Mesh{}), Error);
  Mesh vertices_only;
  vertices_only.vertices = {Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0, 1, 0)};
  CHECK_THROWS_AS(build_triangle_bvh(vertices_only), Error);

  Mesh bad = single_triangle();
  bad.triangles.emplace_back(0, 1, 3);  // one past the last vertex
  CHECK_THROWS_WITH_AS(build_triangle_bvh(bad), doctest::Contains("out-of-range"), Error);
  bad.triangles.back() = Eigen::Vector3i(-1, 1, 2);
  CHECK_THROWS_AS(build_triangle_bvh(bad), Error);

  CHECK_THROWS_AS(build_triangle_bvh(single_triangle(), 0), Error);
  CHECK_THROWS_AS(build_triangle_bvh(single_triangle(), -3), Error);
}

TEST_CASE("bvh: first-order far field is within the documented remainder bound") {
  // For a node (centre c, radius r, area A) and a point p at distance D >= 10 r from c,
  // |sum of exact solid angles - (N.F(c) + sum_ij J_ij M_ij)| <= 3 r^2 A / (D - r)^4.
  std::vector<Mesh> meshes = {test::peg_mesh(1, 3), bvh_soup(300, 99u), single_triangle()};
  std::mt19937 rng(1234);
  std::normal_distribution<double> gauss;
  int checked = 0;
  double worst_ratio = 0;
  for (const Mesh& mesh : meshes) {
    const TriangleBvh bvh = build_triangle_bvh(mesh);
    for (std::size_t i = 0; i < bvh.nodes.size(); ++i) {
      const BvhNode& node = bvh.nodes[i];
      const Vector3d c = v3(node.centroid);
      const double r = node.bbox_max.s[3], area = node.bbox_min.s[3];
      if (!(r > 0) || !(area > 0)) continue;
      const Vector3d normal = v3(node.area_normal);
      Eigen::Matrix3d moment;
      for (int row = 0; row < 3; ++row) moment.row(row) = v3(node.moment[row]).transpose();
      for (double ratio : {10.0, 14.0, 30.0}) {
        for (int trial = 0; trial < 6; ++trial) {
          Vector3d dir(gauss(rng), gauss(rng), gauss(rng));
          // Also look straight along the area vector, where the leading term is largest.
          if (trial == 0 && normal.norm() > 0) dir = normal;
          dir.normalize();
          const Vector3d p = c + ratio * r * dir;
          double exact = 0;
          for (int t = node.links.s[1]; t < node.links.s[1] + node.links.s[2]; ++t)
            exact += solid_angle(p, corner(bvh, t, 0), corner(bvh, t, 1), corner(bvh, t, 2));
          const Vector3d u = c - p;
          const double d = u.norm();
          const Vector3d u_hat = u / d;
          const Eigen::Matrix3d jacobian =
              (Eigen::Matrix3d::Identity() - 3.0 * u_hat * u_hat.transpose()) / (d * d * d);
          const double approx = normal.dot(u / (d * d * d)) + (jacobian.array() * moment.array()).sum();
          const double bound = 3.0 * r * r * area / std::pow(d - r, 4);
          // Slack for the float rounding of the node's data (relative to the zeroth-order size).
          const double slack = 1e-6 * area / (d * d);
          CAPTURE(i);
          CAPTURE(ratio);
          CAPTURE(exact);
          CAPTURE(approx);
          CAPTURE(bound);
          CHECK(std::abs(exact - approx) <= bound + slack);
          worst_ratio = std::max(worst_ratio, std::abs(exact - approx) / bound);
          ++checked;
        }
      }
    }
  }
  CHECK(checked > 100);
  MESSAGE("largest |error| / bound: " << worst_ratio);
  CHECK(worst_ratio < 1.0);
}

TEST_CASE("bvh: first-order expansion is exact to second order (sign conventions)") {
  // With the first-order term the error falls like D^-4; without it, like D^-3. A wrong
  // sign or a transposed moment would leave a D^-3 error: this checks that the moment and
  // its Jacobian contraction follow the kernel's conventions.
  const Mesh mesh = bvh_soup(40, 7u);
  const TriangleBvh bvh = build_triangle_bvh(mesh, 64);
  REQUIRE(bvh.nodes.size() == 1);
  const BvhNode& node = bvh.nodes[0];
  const Vector3d c = v3(node.centroid), normal = v3(node.area_normal);
  const double r = node.bbox_max.s[3];
  Eigen::Matrix3d moment;
  for (int row = 0; row < 3; ++row) moment.row(row) = v3(node.moment[row]).transpose();
  const Vector3d dir = Vector3d(0.3, -0.5, 0.8).normalized();
  auto errors = [&](double ratio) {
    const Vector3d p = c + ratio * r * dir;
    double exact = 0;
    for (int t = 0; t < 40; ++t) exact += solid_angle(p, corner(bvh, t, 0), corner(bvh, t, 1), corner(bvh, t, 2));
    const Vector3d u = c - p;
    const double d = u.norm();
    const Vector3d u_hat = u / d;
    const Eigen::Matrix3d jacobian = (Eigen::Matrix3d::Identity() - 3.0 * u_hat * u_hat.transpose()) / (d * d * d);
    const double zeroth = normal.dot(u / (d * d * d));
    const double first = (jacobian.array() * moment.array()).sum();
    return std::array<double, 2>{std::abs(exact - zeroth), std::abs(exact - zeroth - first)};
  };
  const auto near = errors(20.0), far = errors(40.0);
  CHECK(near[1] < 0.2 * near[0]);
  CHECK(far[1] < 0.2 * far[0]);
  // Doubling the distance: the first-order remainder falls by about 2^4 = 16.
  CHECK(far[1] < near[1] / 10.0);
}
