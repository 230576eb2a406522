#pragma once
// Internal to mesh/procedural/: the checked, typed parameters of each part family,
// the builders that turn them into meshes, and the small mesh-building helpers they
// share. The public entry points are in procedural_parts.h.
#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "mesh/analytic_faces.h"
#include "mesh/mesh.h"

namespace snapfit::procedural {

// Polygon resolution limits: `segments` is a multiple of 8 so that the vertex angles
// 2*pi*i/N include the axis directions and the diagonals (the square's corners).
constexpr double kPi = 3.14159265358979323846;
constexpr int kDefaultSegments = 64;
constexpr int kMaxSegments = 4096;  // keeps the meshes (and memory) bounded
// A hole or peg must leave at least this fraction of the half-width (half-cell) as
// material between it and the square boundary, so no triangle is a sliver.
constexpr double kMinWallFraction = 0.02;

// ---- typed parameters (already checked by procedural_parts.cpp)

struct PegParams {
  double radius = 0;   // circumradius of the N-gon
  double length = 0;   // along +z, bottom face at z = 0
  double chamfer = 0;  // 45-degree bevel of the bottom edge
  int segments = kDefaultSegments;
};

struct HoleBlockParams {
  double peg_radius = 0;  // circumradius of the peg the hole fits
  double clearance = 0;   // gap between the parallel flat faces of peg and hole
  double hole_depth = 0;  // <= height; == height is a through hole
  double width = 0;       // box is [-w/2, w/2]^2 x [-height, 0]
  double height = 0;
  double chamfer = 0;  // 45-degree countersink at the entry (z = 0)
  int segments = kDefaultSegments;

  // Circumradius of the hole's N-gon: the apothem grows by `clearance`, and the
  // apothem of an N-gon is circumradius * cos(pi/N).
  double hole_radius() const { return peg_radius + clearance / std::cos(kPi / segments); }
  bool through() const { return hole_depth == height; }
};

struct ThreePegParams {
  std::array<double, 3> peg_radii{};     // at cells (0,0), (1,1), (2,0)
  std::array<double, 3> peg_heights{};   // peg top above the flat mating face z = 0
  std::array<double, 3> fillet_radii{};  // concave quarter-circle fillet at each peg base
  double cell = 0;                       // footprint: 3 x 2 cells of this size, centred at 0
  double base_thickness = 0;             // base: z in [-base_thickness, mating surface]
  double cover_thickness = 0;            // cover: mating surface up to max(h) + this
  int segments = kDefaultSegments;

  double top() const { return std::max(peg_heights[0], std::max(peg_heights[1], peg_heights[2])) + cover_thickness; }
};

// Peg k of the three-peg pair stands at the centre of cell kPegCells[k] = (ix, iy).
constexpr int kPegCells[3][2] = {{0, 0}, {1, 1}, {2, 0}};

Mesh make_peg(const PegParams& p);
Mesh make_hole_block(const HoleBlockParams& p);
Mesh make_three_peg_base(const ThreePegParams& p);
Mesh make_three_peg_cover(const ThreePegParams& p);

// The analytic faces the parts are tessellations of (procedural_faces.cpp).
std::vector<AnalyticFace> peg_faces(const PegParams& p);
std::vector<AnalyticFace> hole_block_faces(const HoleBlockParams& p);
// The three-peg pair's planes and cylinders, and its fillets as tori (their points stay
// unlabelled): procedural_faces.cpp.
std::vector<AnalyticFace> three_peg_base_faces(const ThreePegParams& p);
std::vector<AnalyticFace> three_peg_cover_faces(const ThreePegParams& p);

// ---- mesh-building helpers

// Area of the regular N-gon of circumradius R: N triangles of area R^2 sin(2pi/N) / 2.
inline double ngon_area(int n, double circumradius) {
  return 0.5 * n * circumradius * circumradius * std::sin(2.0 * kPi / n);
}

// (cos, sin) of the angles 2*pi*i/N, i = 0..N-1, N a multiple of 8, computed in the
// first octant and mirrored/rotated so that axis and diagonal values are exact
// (0, +-1, +-sqrt(1/2)) and the set is exactly symmetric under quarter turns.
inline std::vector<Eigen::Vector2d> unit_ngon(int n) {
  const int quarter = n / 4, eighth = n / 8;
  std::vector<Eigen::Vector2d> first(quarter + 1);  // angles 0 .. pi/2
  for (int i = 0; i <= eighth; ++i) {
    const double a = 2.0 * kPi * i / n;
    first[i] =
        (i == eighth) ? Eigen::Vector2d(std::sqrt(0.5), std::sqrt(0.5)) : Eigen::Vector2d(std::cos(a), std::sin(a));
  }
  for (int i = eighth + 1; i <= quarter; ++i) first[i] = {first[quarter - i].y(), first[quarter - i].x()};
  first[0] = {1.0, 0.0};
  first[quarter] = {0.0, 1.0};
  std::vector<Eigen::Vector2d> out(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector2d v = first[i % quarter];
    for (int q = 0; q < i / quarter; ++q) v = Eigen::Vector2d(-v.y(), v.x());  // quarter turn
    out[i] = v;
  }
  return out;
}

// Accumulates an indexed mesh. Every vertex is added once and referenced by index.
struct MeshBuilder {
  Mesh mesh;

  int vertex(const Eigen::Vector3d& p) {
    mesh.vertices.push_back(p);
    return static_cast<int>(mesh.vertices.size()) - 1;
  }
  void tri(int a, int b, int c) { mesh.triangles.emplace_back(a, b, c); }
  // Quad a-b-c-d, counter-clockwise seen from the side its normal points to.
  void quad(int a, int b, int c, int d) {
    tri(a, b, c);
    tri(a, c, d);
  }

  // Ring of vertices centre + radius * ngon[i] at height z.
  std::vector<int> ring(const std::vector<Eigen::Vector2d>& ngon, const Eigen::Vector2d& centre, double radius,
                        double z) {
    std::vector<int> ids(ngon.size());
    for (size_t i = 0; i < ngon.size(); ++i) {
      const Eigen::Vector2d q = centre + radius * ngon[i];
      ids[i] = vertex({q.x(), q.y(), z});
    }
    return ids;
  }

  // Closes the band between two rings of equal size whose index runs the same way
  // (counter-clockwise seen from +z). The normal of each quad is t x (b - a), with t
  // the direction of increasing index: e.g. a below b on a convex wall points outward.
  void stitch(const std::vector<int>& a, const std::vector<int>& b) {
    const size_t n = a.size();
    for (size_t i = 0; i < n; ++i) {
      const size_t j = (i + 1) % n;
      quad(a[i], a[j], b[j], b[i]);
    }
  }

  // Fan from `centre` over a ring (counter-clockwise seen from +z): normal +z if up.
  void fan(int centre, const std::vector<int>& ring_ids, bool up) {
    const size_t n = ring_ids.size();
    for (size_t i = 0; i < n; ++i) {
      const int a = ring_ids[i], b = ring_ids[(i + 1) % n];
      if (up)
        tri(centre, a, b);
      else
        tri(centre, b, a);
    }
  }
};

}  // namespace snapfit::procedural
