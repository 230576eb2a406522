// Procedural parts (mesh/procedural/): mesh validity (indexed, watertight, outward
// normals, no degenerate triangles) and geometry against closed forms.
#include <algorithm>
#include <array>
#include <cmath>
#include <doctest/doctest.h>
#include <map>
#include <set>
#include <string>
#include <utility>

#include "mesh/procedural/procedural_parts.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using Eigen::Vector3d;
using snapfit::Mesh;
using snapfit::ProceduralPartSpec;

namespace {

using snapfit::test::kPi;

// Signed volume by the divergence theorem: sum over triangles of v0 . (v1 x v2) / 6.
double signed_volume(const Mesh& m) {
  double v = 0;
  for (const auto& t : m.triangles) v += m.vertices[t[0]].dot(m.vertices[t[1]].cross(m.vertices[t[2]])) / 6.0;
  return v;
}

double bbox_diagonal(const Mesh& m) {
  Vector3d lo = m.vertices.front(), hi = lo;
  for (const auto& p : m.vertices) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

// Checks the mesh is a closed, consistently oriented, indexed surface: every undirected
// edge used exactly twice, once in each direction; every vertex used; no two vertices
// at the same place; no degenerate triangles. Returns V - E + F (Euler characteristic).
int check_closed_mesh(const Mesh& m) {
  REQUIRE(!m.triangles.empty());
  const int nv = static_cast<int>(m.vertices.size());
  const double scale = bbox_diagonal(m);
  std::map<std::pair<int, int>, int> directed;
  std::vector<int> used(nv, 0);
  int bad_index = 0, degenerate = 0;
  for (const auto& t : m.triangles) {
    for (int k = 0; k < 3; ++k) {
      if (t[k] < 0 || t[k] >= nv) ++bad_index;
    }
    if (bad_index) break;
    for (int k = 0; k < 3; ++k) {
      ++directed[{t[k], t[(k + 1) % 3]}];
      ++used[t[k]];
    }
    const Vector3d& a = m.vertices[t[0]];
    const double area2 = (m.vertices[t[1]] - a).cross(m.vertices[t[2]] - a).norm();
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || area2 <= 1e-12 * scale * scale) ++degenerate;
  }
  REQUIRE(bad_index == 0);
  CHECK(degenerate == 0);
  int not_once = 0, unpaired = 0;
  for (const auto& [edge, count] : directed) {
    if (count != 1) ++not_once;
    if (!directed.count({edge.second, edge.first})) ++unpaired;
  }
  CHECK(not_once == 0);
  CHECK(unpaired == 0);
  CHECK(std::count(used.begin(), used.end(), 0) == 0);
  // Duplicate (or near-duplicate) vertices: sort by x, compare within a small window.
  std::vector<int> order(nv);
  for (int i = 0; i < nv; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return m.vertices[a].x() < m.vertices[b].x(); });
  const double tol = 1e-9 * scale;
  int duplicates = 0;
  for (int i = 0; i < nv; ++i)
    for (int j = i + 1; j < nv && m.vertices[order[j]].x() - m.vertices[order[i]].x() <= tol; ++j)
      if ((m.vertices[order[j]] - m.vertices[order[i]]).norm() <= tol) ++duplicates;
  CHECK(duplicates == 0);
  return nv - static_cast<int>(directed.size() / 2) + static_cast<int>(m.triangles.size());
}

// Distance from p to triangle abc (closest point by Voronoi regions, Ericson 5.1.5).
double point_triangle_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).norm();
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// Area of the regular N-gon of circumradius R.
double ngon_area(int n, double r) { return 0.5 * n * r * r * std::sin(2 * kPi / n); }

// Frustum between similar polygons of areas a0, a1, height h: h/3 (a0 + a1 + sqrt(a0 a1)).
double frustum_volume(double a0, double a1, double h) { return h / 3 * (a0 + a1 + std::sqrt(a0 * a1)); }

ProceduralPartSpec peg_spec(double r, double length, double chamfer, int segments) {
  return {"peg", {{"radius", r}, {"length", length}, {"chamfer", chamfer}, {"segments", segments}}, {}};
}

ProceduralPartSpec hole_spec(double peg_r, double clearance, double depth, double width, double height, double chamfer,
                             int segments) {
  return {"hole_block",
          {{"peg_radius", peg_r},
           {"clearance", clearance},
           {"hole_depth", depth},
           {"width", width},
           {"height", height},
           {"chamfer", chamfer},
           {"segments", segments}},
          {}};
}

ProceduralPartSpec three_peg_spec(const std::string& type, int segments) {
  return {type,
          {{"cell", 10}, {"base_thickness", 2}, {"cover_thickness", 1.5}, {"segments", segments}},
          {{"peg_radii", {2, 3, 2.5}}, {"peg_heights", {4, 6, 5}}, {"fillet_radii", {0.5, 1.0, 0}}}};
}

std::string error_of(const ProceduralPartSpec& spec) {
  try {
    snapfit::check_procedural_spec(spec);
  } catch (const snapfit::Error& e) {
    // make_procedural_part must refuse the same spec with the same message.
    std::string again;
    try {
      snapfit::make_procedural_part(spec);
    } catch (const snapfit::Error& e2) {
      again = e2.what();
    }
    CHECK(again == std::string(e.what()));
    return e.what();
  }
  return "";
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.rfind(prefix, 0) == 0; }

}  // namespace

TEST_CASE("procedural peg: closed mesh, polygonal volume exact, converges to the cylinder") {
  const double r = 5, length = 30;
  for (int n : {8, 16, 64, 128}) {
    CAPTURE(n);
    const Mesh plain = snapfit::make_procedural_part(peg_spec(r, length, 0, n));
    CHECK(check_closed_mesh(plain) == 2);  // a sphere topologically
    // Prism over the N-gon: (N/2) r^2 sin(2pi/N) * length.
    const double exact = ngon_area(n, r) * length;
    CHECK(std::abs(signed_volume(plain) - exact) <= 1e-12 * exact);

    const double c = 1.5;
    const Mesh bevel = snapfit::make_procedural_part(peg_spec(r, length, c, n));
    CHECK(check_closed_mesh(bevel) == 2);
    // Prism above the bevel plus the polygonal frustum from circumradius r - c to r.
    const double exact_c = ngon_area(n, r) * (length - c) + frustum_volume(ngon_area(n, r - c), ngon_area(n, r), c);
    CHECK(std::abs(signed_volume(bevel) - exact_c) <= 1e-12 * exact_c);
    int outside = 0;
    for (const auto& p : bevel.vertices)
      if (p.z() < 0 || p.z() > length || std::hypot(p.x(), p.y()) > r * (1 + 1e-15)) ++outside;
    CHECK(outside == 0);
  }
  // Inscribed N-gon: relative error (2pi/N)^2 / 6 to leading order, shrinking with N.
  double previous = 1;
  for (int n : {8, 64, 512, 4096}) {
    const double cylinder = kPi * r * r * length;
    const Mesh peg = snapfit::make_procedural_part(peg_spec(r, length, 0, n));
    const double err = std::abs(signed_volume(peg) - cylinder) / cylinder;
    CAPTURE(n);
    CHECK(err < previous);
    CHECK(err <= 1.01 * std::pow(2 * kPi / n, 2) / 6);
    previous = err;
  }
  CHECK(previous < 1e-6);
}

TEST_CASE("procedural hole_block: closed mesh, volume = box - polygonal hole, exact") {
  const double peg_r = 5, width = 20, height = 12;
  for (int n : {8, 64}) {
    for (double clearance : {0.0, 0.2}) {
      for (double chamfer : {0.0, 1.0}) {
        for (double depth : {8.0, height}) {  // blind, through
          CAPTURE(n);
          CAPTURE(clearance);
          CAPTURE(chamfer);
          CAPTURE(depth);
          const Mesh m = snapfit::make_procedural_part(hole_spec(peg_r, clearance, depth, width, height, chamfer, n));
          CHECK(check_closed_mesh(m) == (depth == height ? 0 : 2));  // through hole: a torus
          const double hole_r = peg_r + clearance / std::cos(kPi / n);
          const double hole = ngon_area(n, hole_r) * (depth - chamfer) +
                              frustum_volume(ngon_area(n, hole_r), ngon_area(n, hole_r + chamfer), chamfer);
          const double exact = width * width * height - hole;
          CHECK(std::abs(signed_volume(m) - exact) <= 1e-12 * exact);
          int outside_box = 0;
          for (const auto& p : m.vertices)
            if (std::abs(p.x()) > width / 2 || std::abs(p.y()) > width / 2 || p.z() > 0 || p.z() < -height)
              ++outside_box;
          CHECK(outside_box == 0);
          // The top face (z = 0) faces up, the bottom face (z = -height) down: no folds.
          int top_wrong = 0, bottom_wrong = 0;
          for (const auto& t : m.triangles) {
            const Vector3d a = m.vertices[t[0]], b = m.vertices[t[1]], c = m.vertices[t[2]];
            const double nz = (b - a).cross(c - a).z();
            if (a.z() == 0 && b.z() == 0 && c.z() == 0 && nz <= 0) ++top_wrong;
            if (a.z() == -height && b.z() == -height && c.z() == -height && nz >= 0) ++bottom_wrong;
          }
          CHECK(top_wrong == 0);
          CHECK(bottom_wrong == 0);
        }
      }
    }
  }
}

TEST_CASE("procedural peg in hole_block: inserted at (0,0,-hole_depth), walls exactly clearance apart") {
  const double peg_r = 4, depth = 9, height = 10, width = 14;
  for (int n : {16, 64}) {
    for (double hole_chamfer : {0.0, 0.8}) {
      for (double clearance : {0.0, 0.01, 0.5}) {
        CAPTURE(n);
        CAPTURE(hole_chamfer);
        CAPTURE(clearance);
        const Mesh hole =
            snapfit::make_procedural_part(hole_spec(peg_r, clearance, depth, width, height, hole_chamfer, n));
        Mesh peg = snapfit::make_procedural_part(peg_spec(peg_r, 15, 0.3, n));
        for (auto& p : peg.vertices) p.z() -= depth;  // the inserted pose
        const double hole_r = peg_r + clearance / std::cos(kPi / n);
        auto radius = [](const Vector3d& p) { return std::hypot(p.x(), p.y()); };

        // The hole's straight side-wall triangles: all corners on the hole circumradius.
        std::vector<std::array<Vector3d, 3>> wall;
        for (const auto& t : hole.triangles) {
          bool on_wall = true;
          for (int k = 0; k < 3; ++k)
            on_wall = on_wall && std::abs(radius(hole.vertices[t[k]]) - hole_r) <= 1e-12 * hole_r &&
                      hole.vertices[t[k]].z() <= -hole_chamfer + 1e-12;
          if (on_wall) wall.push_back({hole.vertices[t[0]], hole.vertices[t[1]], hole.vertices[t[2]]});
        }
        CHECK(wall.size() == static_cast<size_t>(2 * n));

        // Every peg side-wall vertex inside the hole's straight part is at distance
        // exactly `clearance` from the hole's walls.
        double min_d = 1e300, max_d = 0;
        int wall_vertices = 0;
        for (const auto& p : peg.vertices) {
          if (std::abs(radius(p) - peg_r) > 1e-12 * peg_r || p.z() > -hole_chamfer) continue;
          ++wall_vertices;
          double d = 1e300;
          for (const auto& t : wall) d = std::min(d, point_triangle_distance(p, t[0], t[1], t[2]));
          min_d = std::min(min_d, d);
          max_d = std::max(max_d, d);
        }
        CHECK(wall_vertices == n);  // the shoulder ring at z = 0.3 - depth
        CHECK(std::abs(min_d - clearance) <= 1e-9);
        CHECK(std::abs(max_d - clearance) <= 1e-9);

        // No peg vertex below the block's top face is outside the hole: above the hole
        // bottom and inside every face plane of the hole's N-gon at that depth.
        int outside = 0;
        for (const auto& p : peg.vertices) {
          if (p.z() >= 0) continue;
          if (p.z() < -depth - 1e-12) ++outside;
          const double circum = hole_r + std::max(0.0, p.z() + hole_chamfer);  // countersink
          const double apothem = circum * std::cos(kPi / n);
          for (int j = 0; j < n; ++j) {
            const double a = (2 * j + 1) * kPi / n;  // face normal between vertices j, j + 1
            if (p.x() * std::cos(a) + p.y() * std::sin(a) > apothem + 1e-12) {
              ++outside;
              break;
            }
          }
        }
        CHECK(outside == 0);
      }
    }
  }
}

TEST_CASE("procedural three-peg pair: base + cover fill the box, base volume converges") {
  const double cell = 10, bt = 2, ct = 1.5;
  const std::array<double, 3> r{2, 3, 2.5}, h{4, 6, 5}, f{0.5, 1.0, 0};
  const double top = 6 + ct;
  const double box = 3 * cell * 2 * cell * (bt + top);
  // Continuous base: slab + cylinders + fillet rings by Pappus (cross-section area
  // f^2 (1 - pi/4), centroid f (10 - 3pi)/(12 - 3pi) from the corner, so at radius r + d).
  double continuous = 3 * cell * 2 * cell * bt, pegs = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = f[k] * (10 - 3 * kPi) / (12 - 3 * kPi);
    const double part = kPi * r[k] * r[k] * h[k] + 2 * kPi * (r[k] + d) * f[k] * f[k] * (1 - kPi / 4);
    continuous += part;
    pegs += part;
  }

  // The mesh's exact volume: each ring is an N-gon of circumradius rho, and the N-gon's
  // area is A_N(1) rho^2 against pi rho^2 for the circle, so sweeping a (rho, z) profile
  // region around the N-gon gives (A_N(1) / pi) times its volume of revolution (Pappus:
  // 2 pi * centroid rho * area). The profile is the peg rectangle plus the fillet corner
  // bounded by the chords through the rows (N/8 intervals along the quarter circle).
  auto polygonal_base = [&](int n) {
    double v = 3 * cell * 2 * cell * bt;
    for (int k = 0; k < 3; ++k) {
      double revolved = kPi * r[k] * r[k] * h[k];
      if (f[k] > 0) {
        const int rows = std::max(1, n / 8);
        std::vector<std::array<double, 2>> poly{{r[k], 0.0}};  // (rho, z), counter-clockwise
        for (int j = rows; j >= 0; --j) {
          const double psi = 0.5 * kPi * j / rows;
          poly.push_back({r[k] + f[k] - f[k] * std::cos(psi), f[k] - f[k] * std::sin(psi)});
        }
        double moment = 0;  // first moment in rho of the area, shoelace form
        for (size_t i = 0; i < poly.size(); ++i) {
          const auto& a = poly[i];
          const auto& b = poly[(i + 1) % poly.size()];
          const double cross = a[0] * b[1] - b[0] * a[1];
          moment += (a[0] + b[0]) * cross / 6;
        }
        revolved += 2 * kPi * moment;
      }
      v += ngon_area(n, 1.0) / kPi * revolved;
    }
    return v;
  };

  std::map<int, double> error;
  for (int n : {16, 64, 128}) {
    CAPTURE(n);
    const Mesh base = snapfit::make_procedural_part(three_peg_spec("three_peg_base", n));
    const Mesh cover = snapfit::make_procedural_part(three_peg_spec("three_peg_cover", n));
    CHECK(check_closed_mesh(base) == 2);
    CHECK(check_closed_mesh(cover) == 2);
    const double vb = signed_volume(base), vc = signed_volume(cover);
    CHECK(vb > 0);  // outward normals (closed, consistently oriented, positive volume)
    CHECK(vc > 0);
    CHECK(std::abs(vb + vc - box) <= 1e-9 * box);

    // Extents: base in [-bt, max h], cover in [0, top], both over the footprint.
    for (const auto* m : {&base, &cover}) {
      Vector3d lo = m->vertices.front(), hi = lo;
      for (const auto& p : m->vertices) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      CHECK(lo.x() == -1.5 * cell);
      CHECK(hi.x() == 1.5 * cell);
      CHECK(lo.y() == -cell);
      CHECK(hi.y() == cell);
      CHECK(lo.z() == (m == &base ? -bt : 0.0));
      CHECK(hi.z() == (m == &base ? 6.0 : top));
    }

    // The mating surface: base vertices above its bottom, cover vertices below its top;
    // the two sets are the same points, bit for bit.
    std::set<std::array<double, 3>> base_mating, cover_mating;
    for (const auto& p : base.vertices)
      if (p.z() > -bt / 2) base_mating.insert({p.x(), p.y(), p.z()});
    for (const auto& p : cover.vertices)
      if (p.z() < top - ct / 2) cover_mating.insert({p.x(), p.y(), p.z()});
    CHECK(base_mating.size() > 0);
    CHECK(base_mating == cover_mating);

    CHECK(std::abs(vb - polygonal_base(n)) <= 1e-12 * box);

    // Folds in the mating surface would show as triangles facing down: none do, and
    // the flat parts (z = 0) face straight up.
    int facing_down = 0, flat_not_up = 0;
    for (const auto& t : base.triangles) {
      const Vector3d a = base.vertices[t[0]], b = base.vertices[t[1]], c = base.vertices[t[2]];
      if (std::min({a.z(), b.z(), c.z()}) < 0) continue;  // side walls and bottom
      const Vector3d normal = (b - a).cross(c - a);
      if (normal.z() < -1e-12 * normal.norm()) ++facing_down;
      if (a.z() == 0 && b.z() == 0 && c.z() == 0 && normal.z() <= 0) ++flat_not_up;
    }
    CHECK(facing_down == 0);
    CHECK(flat_not_up == 0);

    error[n] = std::abs(vb - continuous);
    INFO("three_peg_base segments " << n << ": volume " << vb << ", continuous " << continuous << ", error " << error[n]
                                    << " (relative " << error[n] / continuous << ")");
    // Polygonal (inscribed N-gon) and chord errors are O((2pi/N)^2) of the pegs' volume.
    CHECK(error[n] <= std::pow(2 * kPi / n, 2) * pegs);
  }
  CHECK(error[64] < error[16] / 3);
  CHECK(error[128] < error[64] / 3);
}

TEST_CASE("procedural three-peg: the pegs stand at cells (0,0), (1,1), (2,0) with their radii") {
  const Mesh base = snapfit::make_procedural_part(three_peg_spec("three_peg_base", 32));
  const double cell = 10;
  const std::array<std::array<double, 2>, 3> centres{{{-cell, -cell / 2}, {0, cell / 2}, {cell, -cell / 2}}};
  const std::array<double, 3> r{2, 3, 2.5}, h{4, 6, 5};
  for (int k = 0; k < 3; ++k) {
    CAPTURE(k);
    // The peg top cap: vertices at the peg's height, all within its radius of its centre.
    int on_top = 0;
    double max_radius = 0;
    for (const auto& p : base.vertices) {
      if (p.z() != h[k]) continue;
      const double d = std::hypot(p.x() - centres[k][0], p.y() - centres[k][1]);
      if (d > cell / 2) continue;
      ++on_top;
      max_radius = std::max(max_radius, d);
    }
    CHECK(on_top == 33);  // ring + centre
    CHECK(max_radius == doctest::Approx(r[k]).epsilon(1e-12));
  }
}

TEST_CASE("procedural parts: valid specs pass the check, defaults apply") {
  CHECK_NOTHROW(snapfit::check_procedural_spec({"peg", {{"radius", 1}, {"length", 2}}, {}}));
  const Mesh peg = snapfit::make_procedural_part({"peg", {{"radius", 1}, {"length", 2}}, {}});
  CHECK(peg.vertices.size() == 2 * 64 + 2);  // default segments 64, no chamfer
  CHECK_NOTHROW(snapfit::check_procedural_spec(
      {"hole_block", {{"peg_radius", 1}, {"hole_depth", 2}, {"width", 3}, {"height", 2}}, {}}));
  CHECK_NOTHROW(snapfit::check_procedural_spec({"three_peg_cover",
                                                {{"cell", 1}, {"base_thickness", 1}, {"cover_thickness", 1}},
                                                {{"peg_radii", {0.1, 0.2, 0.3}}, {"peg_heights", {1, 1, 1}}}}));
}

TEST_CASE("procedural parts: invalid specs throw snapfit::Error naming the field") {
  const ProceduralPartSpec three = three_peg_spec("three_peg_base", 64);
  struct Case {
    const char* what;
    ProceduralPartSpec spec;
    std::string field;
  };
  auto with_number = [](ProceduralPartSpec s, const std::string& name, double v) {
    s.numbers[name] = v;
    return s;
  };
  auto with_array = [](ProceduralPartSpec s, const std::string& name, std::vector<double> v) {
    s.arrays[name] = std::move(v);
    return s;
  };
  auto without = [](ProceduralPartSpec s, const std::string& name) {
    s.numbers.erase(name);
    s.arrays.erase(name);
    return s;
  };
  const ProceduralPartSpec peg = peg_spec(5, 30, 0, 64);
  const ProceduralPartSpec hole = hole_spec(5, 0.1, 8, 20, 10, 1, 64);
  const std::vector<Case> cases = {
      {"negative radius", with_number(peg, "radius", -1), "radius"},
      {"zero radius", with_number(peg, "radius", 0), "radius"},
      {"NaN length", with_number(peg, "length", std::nan("")), "length"},
      {"missing length", without(peg, "length"), "length"},
      {"segments 12", with_number(peg, "segments", 12), "segments"},
      {"segments 4", with_number(peg, "segments", 4), "segments"},
      {"segments 64.5", with_number(peg, "segments", 64.5), "segments"},
      {"segments huge", with_number(peg, "segments", 1e12), "segments"},
      {"unknown parameter", with_number(peg, "wibble", 1), "wibble"},
      {"array for a number", with_array(peg, "radius", {1, 2, 3}), "radius"},
      {"chamfer == radius", with_number(peg, "chamfer", 5), "chamfer"},
      {"chamfer > radius", with_number(peg, "chamfer", 7), "chamfer"},
      {"negative chamfer", with_number(peg, "chamfer", -0.1), "chamfer"},
      {"chamfer >= length", with_number(with_number(peg, "radius", 50), "chamfer", 30), "chamfer"},
      {"missing peg_radius", without(hole, "peg_radius"), "peg_radius"},
      {"negative clearance", with_number(hole, "clearance", -0.01), "clearance"},
      {"hole deeper than block", with_number(hole, "hole_depth", 11), "hole_depth"},
      {"hole chamfer >= depth", with_number(hole, "chamfer", 8), "chamfer"},
      {"block too narrow", with_number(hole, "width", 2 * 6.1), "width"},
      {"missing width", without(hole, "width"), "width"},
      {"fillet too large for the cell", with_array(three, "fillet_radii", {0.5, 2.0, 0}), "fillet_radii[1]"},
      {"peg too large for the cell", with_array(three, "peg_radii", {2, 3, 5}), "peg_radii[2]"},
      {"fillet above the peg top", with_array(three, "fillet_radii", {0.5, 1.0, 5}), "fillet_radii[2]"},
      {"negative fillet", with_array(three, "fillet_radii", {0.5, -1.0, 0}), "fillet_radii[1]"},
      {"peg_radii with 2 entries", with_array(three, "peg_radii", {2, 3}), "peg_radii"},
      {"peg_radii not distinct", with_array(three, "peg_radii", {2, 3, 2}), "peg_radii"},
      {"peg_heights zero", with_array(three, "peg_heights", {4, 0, 5}), "peg_heights[1]"},
      {"missing peg_heights", without(three, "peg_heights"), "peg_heights"},
      {"number for an array", with_number(without(three, "peg_radii"), "peg_radii", 2), "peg_radii"},
      {"missing cell", without(three, "cell"), "cell"},
      {"negative cover_thickness", with_number(three, "cover_thickness", -1), "cover_thickness"},
      {"unknown type", ProceduralPartSpec{"cone", {{"radius", 1}}, {}}, "type"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.what);
    const std::string message = error_of(c.spec);
    CAPTURE(message);
    CHECK(starts_with(message, c.field + ":"));
  }
  // Several unknown names: all of them are named.
  const std::string message = error_of(with_number(with_number(peg, "wibble", 1), "zap", 2));
  CHECK(message.find("wibble") != std::string::npos);
  CHECK(message.find("zap") != std::string::npos);
  CHECK_THROWS_AS(snapfit::make_procedural_part(with_number(peg, "radius", -1)), snapfit::Error);
}
