// Winding number by sign propagation (engine/fields/winding_propagation.h): the closed-mesh
// test, the "surface cannot cross" components, rounding of the seeds, and the whole
// path against the full winding kernel at every point and the double-precision
// reference (tests/descriptor_reference.h), including overlapping shells (w = 2) and
// open or inconsistently oriented meshes (full path).
#include <cmath>
#include <doctest/doctest.h>
#include <string>
#include <tbb/parallel_for.h>
#include <vector>

#include "engine/fields/descriptors.h"
#include "engine/fields/winding_propagation.h"
#include "mesh/procedural/procedural_parts.h"
#include "tests/descriptor_reference.h"
#include "tests/test_engine_support.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

Mesh peg(double radius, double length, int segments) {
  return make_procedural_part({"peg", {{"radius", radius}, {"length", length}, {"segments", double(segments)}}, {}});
}

Mesh three_peg_base(int segments) {
  return make_procedural_part(
      {"three_peg_base",
       {{"cell", 20}, {"base_thickness", 8}, {"cover_thickness", 6}, {"segments", double(segments)}},
       {{"peg_radii", {3, 4.5, 6}}, {"peg_heights", {8, 10, 12}}, {"fillet_radii", {1, 1.5, 2}}}});
}

Mesh hole_block() {
  return make_procedural_part({"hole_block",
                               {{"peg_radius", 5},
                                {"clearance", 0},
                                {"hole_depth", 20},
                                {"width", 30},
                                {"height", 30},
                                {"chamfer", 0.5},
                                {"segments", 32}},
                               {}});
}

// Both meshes in one (two closed shells; w = 2 where they overlap).
Mesh merged(const Mesh& a, const Mesh& b, const Vector3d& shift) {
  Mesh m = a;
  const int base = static_cast<int>(m.vertices.size());
  for (const Vector3d& v : b.vertices) m.vertices.push_back(v + shift);
  for (const Eigen::Vector3i& t : b.triangles) m.triangles.emplace_back(t[0] + base, t[1] + base, t[2] + base);
  return m;
}

// Every triangle with its own three vertices (an STL-like soup).
Mesh unindexed(const Mesh& m) {
  Mesh out;
  for (const Eigen::Vector3i& t : m.triangles) {
    const int base = static_cast<int>(out.vertices.size());
    for (int k = 0; k < 3; ++k) out.vertices.push_back(m.vertices[t[k]]);
    out.triangles.emplace_back(base, base + 1, base + 2);
  }
  return out;
}

// About n points along the longest side of the mesh's box padded by 15%, with the
// origin shifted off the round coordinates of the procedural parts' faces.
GridSpec grid_for(const Mesh& m, int n) {
  Eigen::AlignedBox3d box;
  for (const Vector3d& v : m.vertices) box.extend(v);
  const double pad = 0.15 * box.sizes().maxCoeff();
  GridSpec g;
  g.spacing = (box.sizes().maxCoeff() + 2 * pad) / (n - 1);
  for (int a = 0; a < 3; ++a) g.dims[a] = static_cast<int>(std::ceil((box.sizes()[a] + 2 * pad) / g.spacing)) + 1;
  g.origin = box.min().array() - pad + 0.1234 * g.spacing;
  return g;
}

Vector3d point_of(const GridSpec& g, std::size_t id) { return g.point(id); }

DescriptorFields winding_fields(const Mesh& mesh, const GridSpec& grid, bool propagate) {
  DescriptorParams params;
  params.kind = DescriptorKind::indicator;
  params.tolerance = 0.1;
  DescriptorOptions options;
  options.program_cache = test::test_program_cache();
  options.winding_sign_propagation = propagate;
  options.indicator_signed_distance = true;
  return compute_descriptors(test::test_context(), mesh, grid, params, options);
}

// Propagated against full: both within their bounds of one value everywhere, and equal
// wherever the full kernel's bound decides the integer. Returns the propagated fields.
DescriptorFields check_against_full(const std::string& name, const Mesh& mesh, const GridSpec& grid) {
  INFO(name);
  REQUIRE(mesh_is_closed(mesh));
  const DescriptorFields prop = winding_fields(mesh, grid, true);
  const DescriptorFields full = winding_fields(mesh, grid, false);
  CHECK(prop.winding_method == "sign propagation");
  CHECK(full.winding_method == "full");
  CHECK(full.winding_kernel_points == grid.count());
  CHECK(prop.winding_kernel_points < grid.count() / 4);
  std::size_t decided = 0, equal = 0, outside_bounds = 0, unproven = 0;
  double excess = 0;  // largest |w_prop - w_full| - (bound_prop + bound_full)
  for (std::size_t i = 0; i < grid.count(); ++i) {
    const double wp = prop.winding[i], bp = prop.winding_bound[i];
    const double wf = full.winding[i], bf = full.winding_bound[i];
    if (bp > 0)
      ++unproven;
    else
      CHECK(wp == std::nearbyint(wp));
    excess = std::max(excess, std::abs(wp - wf) - (bp + bf));
    // The bounds hold up to the float rounding of the kernel's sum of solid angles.
    if (std::abs(wp - wf) > bp + bf + 1e-4) ++outside_bounds;
    const double k = std::nearbyint(wf);
    if (std::abs(wf - k) + bf < 0.49) {
      ++decided;
      if (wp == k) ++equal;
    }
  }
  MESSAGE(name << ": " << grid.count() << " points, kernel at " << prop.winding_kernel_points << " seeds; " << decided
               << " decided by the full kernel, " << equal << " equal; " << unproven
               << " propagated values not proven integers; largest excess over the summed bounds " << excess);
  CHECK(outside_bounds == 0);
  CHECK(decided > grid.count() * 9 / 10);
  CHECK(equal == decided);
  // The signed distance's sign follows w in both.
  CHECK(prop.signed_distance.size() == grid.count());
  return prop;
}

}  // namespace

TEST_CASE("winding propagation: closed-mesh test") {
  const Mesh p = peg(1.0, 2.0, 16);
  CHECK(mesh_is_closed(p));
  CHECK(mesh_is_closed(three_peg_base(16)));
  CHECK(mesh_is_closed(hole_block()));
  CHECK(mesh_is_closed(unindexed(p)));  // exactly equal vertices are welded
  CHECK(mesh_is_closed(merged(p, p, Vector3d(0.3, 0, 0))));
  {
    Mesh open = p;
    open.triangles.pop_back();
    CHECK_FALSE(mesh_is_closed(open));
  }
  {
    Mesh flipped = p;
    std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
    CHECK_FALSE(mesh_is_closed(flipped));
  }
  {
    // The same triangle twice with the same orientation: every edge unbalanced.
    Mesh doubled = p;
    doubled.triangles.push_back(p.triangles[0]);
    CHECK_FALSE(mesh_is_closed(doubled));
  }
  CHECK_FALSE(mesh_is_closed(Mesh{}));
}

TEST_CASE("winding propagation: components split where the surface may pass, seeds are the farthest points") {
  // A 6 x 3 x 3 grid, spacing 1, with a wall of small distances at i = 2 and 3.
  GridSpec g;
  g.spacing = 1.0;
  g.dims = {6, 3, 3};
  std::vector<float> d(g.count());
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 6; ++i) d[g.index(i, j, k)] = (i == 2 || i == 3) ? 0.4f : 0.8f + 0.01f * (i + j + k);
  // 0.4 + 0.4 < 1 (may cross), 0.4 + 0.8 > 1 (cannot cross): {i <= 2} and {i >= 3}.
  const WindingComponents c = winding_components(g, d, 1e-6);
  REQUIRE(c.seeds.size() == 2);
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 0; i < 6; ++i) CHECK(c.component[g.index(i, j, k)] == (i <= 2 ? 0 : 1));
  CHECK(c.seeds[0] == static_cast<std::int64_t>(g.index(1, 2, 2)));
  CHECK(c.seeds[1] == static_cast<std::int64_t>(g.index(5, 2, 2)));
  // A sum exactly at the spacing (plus slack) may cross: the wall splits every point.
  std::fill(d.begin(), d.end(), 0.5f);
  CHECK(winding_components(g, d, 1e-6).seeds.size() == g.count());

  // Rounding: proven integers get bound 0; the rest keep the seed's value and bound.
  std::vector<float> w, b;
  const std::size_t proven = propagate_winding(c, {0.97f, 0.6f}, {0.01f, 0.2f}, w, b);
  CHECK(proven == 1);
  CHECK(w[g.index(0, 0, 0)] == 1.0f);
  CHECK(b[g.index(0, 0, 0)] == 0.0f);
  CHECK(w[g.index(4, 0, 0)] == 0.6f);
  CHECK(b[g.index(4, 0, 0)] == 0.2f);
}

TEST_CASE("winding propagation: the same w as the full kernel on closed meshes") {
  check_against_full("peg, 16 segments", peg(1.0, 2.0, 16), grid_for(peg(1.0, 2.0, 16), 24));
  check_against_full("unindexed peg", unindexed(peg(1.0, 2.0, 24)), grid_for(peg(1.0, 2.0, 24), 20));
  const Mesh base = three_peg_base(16);
  check_against_full("three_peg_base, 16 segments", base, grid_for(base, 32));
  const Mesh block = hole_block();
  check_against_full("hole_block", block, grid_for(block, 28));
}

TEST_CASE("winding propagation: overlapping closed shells give w = 2 in the overlap") {
  const Mesh p = peg(1.0, 2.0, 24);
  const Mesh two = merged(p, p, Vector3d(0.7, 0.2, 0.3));
  const GridSpec grid = grid_for(two, 26);
  const DescriptorFields f = check_against_full("two overlapping pegs", two, grid);
  // Against the double-precision reference at every point off the surface.
  std::vector<int> twos(grid.count(), 0), bad(grid.count(), 0);
  tbb::parallel_for(std::size_t(0), grid.count(), [&](std::size_t i) {
    const double ref = test::reference_winding(two, point_of(grid, i));
    if (std::abs(ref - std::nearbyint(ref)) > 0.25) return;  // on or within round-off of the surface
    if (f.winding[i] != std::nearbyint(ref)) bad[i] = 1;
    if (f.winding[i] == 2.0f) twos[i] = 1;
  });
  std::size_t n_two = 0, n_bad = 0;
  for (std::size_t i = 0; i < grid.count(); ++i) n_two += twos[i], n_bad += bad[i];
  MESSAGE("two overlapping pegs: " << n_two << " points with w = 2, " << n_bad << " differ from the reference");
  CHECK(n_two > 100);
  CHECK(n_bad == 0);
}

TEST_CASE("winding propagation: open or inconsistently oriented meshes use the full kernel everywhere") {
  Mesh open = peg(1.0, 2.0, 16);
  open.triangles.erase(open.triangles.begin() + 5);
  Mesh flipped = peg(1.0, 2.0, 16);
  std::swap(flipped.triangles[7][1], flipped.triangles[7][2]);
  for (const Mesh* m : {&open, &flipped}) {
    const GridSpec grid = grid_for(*m, 16);
    const DescriptorFields f = winding_fields(*m, grid, true);
    CHECK(f.winding_method == "full");
    CHECK(f.winding_kernel_points == grid.count());
    // Not piecewise integer: some point off the surface has a fractional w.
    bool fractional = false;
    for (std::size_t i = 0; i < grid.count(); ++i)
      if (std::abs(f.winding[i] - std::nearbyint(f.winding[i])) > 0.01 + f.winding_bound[i]) fractional = true;
    CHECK(fractional);
  }
}
