// The three-peg base and its exact complement, the cover (procedural_parts.h).
//
// Both share one mating surface, built once from the same vertex positions:
//  - the footprint [-3c/2, 3c/2] x [-c, c] (c = cell) is 3 x 2 square cells; along every
//    cell edge the nodes are tan-spaced, u_j = (c/2) tan(phi_j), phi_j uniform in
//    [-pi/4, pi/4] with M = N/4 intervals, so neighbouring cells conform;
//  - a cell without a peg is the tensor grid of those nodes at z = 0;
//  - a peg cell is rings around the peg axis at the N-gon angles 2*pi*i/N: the peg top
//    (fan), the peg wall, the fillet rows (quarter-circle profile), and the cell's
//    boundary nodes. The ray from the cell centre at angle 2*pi*i/N meets the cell
//    boundary exactly at a tan-spaced node (tan of the ray angle relative to the edge's
//    normal), so node i of the boundary lies on ray i and the last band is convex quads.
// The base adds side walls down to z = -base_thickness and a flat bottom; the cover
// takes the mating surface with reversed orientation and adds side walls up to
// z = max(peg_heights) + cover_thickness and a flat top. The union is the box.
#include <cmath>

#include "mesh/procedural/procedural_internal.h"

namespace snapfit::procedural {

namespace {

struct MatingSurface {
  Mesh mesh;                   // z = h(x, y) with the pegs; normals up (the base's outside)
  std::vector<int> boundary;   // footprint boundary vertices, counter-clockwise from +z
  std::vector<double> gx, gy;  // global node coordinates: 3M + 1 along x, 2M + 1 along y
};

// Tan-spaced nodes u_j = (cell/2) tan(-pi/4 + j*pi/(2M)), j = 0..M, exactly antisymmetric
// with exact end points +-cell/2 and exact 0 in the middle (M is even).
std::vector<double> tan_nodes(int m, double cell) {
  std::vector<double> u(m + 1);
  for (int j = 0; j <= m / 2; ++j) {
    u[j] = j == 0 ? -0.5 * cell : 0.5 * cell * std::tan(-0.25 * kPi + j * 0.5 * kPi / m);
    u[m - j] = -u[j];
  }
  u[m / 2] = 0.0;
  return u;
}

// Local node (a, b) in 0..M of a cell's boundary hit by the ray at angle 2*pi*i/N, N = 4M,
// measured from the cell centre: the right edge covers angles [-pi/4, pi/4], and so on.
std::pair<int, int> boundary_node(int i, int m) {
  const int n = 4 * m, h = m / 2;
  if (i >= n - h) i -= n;                 // right edge, angles just below 0
  if (i <= h) return {m, h + i};          // right edge, x = +cell/2
  if (i <= 3 * h) return {3 * h - i, m};  // top edge, y = +cell/2
  if (i <= 5 * h) return {0, 5 * h - i};  // left edge, x = -cell/2
  return {i - 5 * h, 0};                  // bottom edge, y = -cell/2
}

MatingSurface build_mating_surface(const ThreePegParams& p) {
  const int n = p.segments, m = n / 4;
  const int fillet_rows = std::max(1, n / 8);  // intervals along each quarter-circle fillet
  const auto ngon = unit_ngon(n);
  const std::vector<double> u = tan_nodes(m, p.cell);

  MatingSurface s;
  s.gx.resize(3 * m + 1);
  s.gy.resize(2 * m + 1);
  for (int k = 0; k <= 3 * m; ++k) {
    const int cx = std::min(k / m, 2);
    s.gx[k] = (cx - 1) * p.cell + u[k - cx * m];
  }
  for (int k = 0; k <= 2 * m; ++k) {
    const int cy = std::min(k / m, 1);
    s.gy[k] = (cy - 0.5) * p.cell + u[k - cy * m];
  }

  MeshBuilder b;
  // Grid nodes at z = 0, created on first use so peg-cell interiors get none.
  std::vector<int> grid_id((3 * m + 1) * (2 * m + 1), -1);
  auto node = [&](int a, int c) {
    int& id = grid_id[a * (2 * m + 1) + c];
    if (id < 0) id = b.vertex({s.gx[a], s.gy[c], 0.0});
    return id;
  };

  for (int cx = 0; cx < 3; ++cx) {
    for (int cy = 0; cy < 2; ++cy) {
      int peg = -1;
      for (int k = 0; k < 3; ++k)
        if (kPegCells[k][0] == cx && kPegCells[k][1] == cy) peg = k;

      if (peg < 0) {  // flat cell: tensor grid, normal +z
        for (int a = cx * m; a < (cx + 1) * m; ++a)
          for (int c = cy * m; c < (cy + 1) * m; ++c)
            b.quad(node(a, c), node(a + 1, c), node(a + 1, c + 1), node(a, c + 1));
        continue;
      }

      const double r = p.peg_radii[peg], h = p.peg_heights[peg], f = p.fillet_radii[peg];
      const Eigen::Vector2d centre((cx - 1) * p.cell, (cy - 0.5) * p.cell);
      std::vector<int> border(n);
      for (int i = 0; i < n; ++i) {
        const auto [a, c] = boundary_node(i, m);
        border[i] = node(cx * m + a, cy * m + c);
      }
      // Rows from the peg wall's foot outward. Fillet: quarter circle centred at
      // (rho, z) = (r + f, f), radius f: rho = r + f - f cos(psi), z = f - f sin(psi),
      // psi in [0, pi/2]; psi = 0 is (r, f) (vertical tangent), pi/2 is (r + f, 0).
      std::vector<std::vector<int>> rows;
      if (f > 0) {
        for (int k = 0; k <= fillet_rows; ++k) {
          const double psi = 0.5 * kPi * k / fillet_rows;
          const double rho = k == 0 ? r : k == fillet_rows ? r + f : r + f - f * std::cos(psi);
          const double z = k == 0 ? f : k == fillet_rows ? 0.0 : f - f * std::sin(psi);
          rows.push_back(b.ring(ngon, centre, rho, z));
        }
      } else {
        rows.push_back(b.ring(ngon, centre, r, 0.0));
      }
      const std::vector<int> top = b.ring(ngon, centre, r, h);
      b.fan(b.vertex({centre.x(), centre.y(), h}), top, /*up=*/true);               // peg top
      b.stitch(rows.front(), top);                                                  // peg wall
      for (size_t k = 0; k + 1 < rows.size(); ++k) b.stitch(rows[k + 1], rows[k]);  // fillet
      b.stitch(border, rows.back());  // flat band out to the cell boundary, normal +z
    }
  }

  // Footprint boundary, counter-clockwise seen from +z, starting at (-3c/2, -c).
  for (int a = 0; a < 3 * m; ++a) s.boundary.push_back(node(a, 0));
  for (int c = 0; c < 2 * m; ++c) s.boundary.push_back(node(3 * m, c));
  for (int a = 3 * m; a > 0; --a) s.boundary.push_back(node(a, 2 * m));
  for (int c = 2 * m; c > 0; --c) s.boundary.push_back(node(0, c));
  s.mesh = std::move(b.mesh);
  return s;
}

// Side walls from the mating surface's boundary to a flat face at height z (tensor grid
// of the global nodes), closing `b`. `below`: the face is under the mating surface.
void close_with_flat_face(MeshBuilder& b, const MatingSurface& s, double z, bool below) {
  const int nx = static_cast<int>(s.gx.size()), ny = static_cast<int>(s.gy.size());
  std::vector<int> flat(nx * ny);
  for (int a = 0; a < nx; ++a)
    for (int c = 0; c < ny; ++c) flat[a * ny + c] = b.vertex({s.gx[a], s.gy[c], z});
  auto at = [&](int a, int c) { return flat[a * ny + c]; };
  for (int a = 0; a + 1 < nx; ++a) {
    for (int c = 0; c + 1 < ny; ++c) {
      if (below)
        b.quad(at(a, c), at(a, c + 1), at(a + 1, c + 1), at(a + 1, c));  // normal -z
      else
        b.quad(at(a, c), at(a + 1, c), at(a + 1, c + 1), at(a, c + 1));  // normal +z
    }
  }
  // The flat face's boundary in the same counter-clockwise order as s.boundary.
  std::vector<int> ring;
  for (int a = 0; a + 1 < nx; ++a) ring.push_back(at(a, 0));
  for (int c = 0; c + 1 < ny; ++c) ring.push_back(at(nx - 1, c));
  for (int a = nx - 1; a > 0; --a) ring.push_back(at(a, ny - 1));
  for (int c = ny - 1; c > 0; --c) ring.push_back(at(0, c));
  if (below)
    b.stitch(ring, s.boundary);  // lower ring first: normals outward
  else
    b.stitch(s.boundary, ring);
}

}  // namespace

Mesh make_three_peg_base(const ThreePegParams& p) {
  MatingSurface s = build_mating_surface(p);
  MeshBuilder b;
  b.mesh = s.mesh;
  close_with_flat_face(b, s, -p.base_thickness, /*below=*/true);
  return std::move(b.mesh);
}

Mesh make_three_peg_cover(const ThreePegParams& p) {
  MatingSurface s = build_mating_surface(p);
  MeshBuilder b;
  b.mesh.vertices = s.mesh.vertices;                                          // same indices, so s.boundary stays valid
  for (const Eigen::Vector3i& t : s.mesh.triangles) b.tri(t[0], t[2], t[1]);  // normals down
  close_with_flat_face(b, s, p.top(), /*below=*/false);
  return std::move(b.mesh);
}

}  // namespace snapfit::procedural
