#include "scheduler/vps/voxmap.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <string>

#include "mesh/mesh_distance.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Triangle-box overlap by the separating axis theorem (Akenine-Moeller 2001): the box's
// three axes, the triangle's normal and the nine edge-axis cross products.
bool triangle_overlaps_box(const Eigen::Vector3d& centre, double half, const Eigen::Vector3d& v0,
                           const Eigen::Vector3d& v1, const Eigen::Vector3d& v2) {
  const Eigen::Vector3d a = v0 - centre, b = v1 - centre, c = v2 - centre;
  const auto separated = [&](const Eigen::Vector3d& axis) {
    const double pa = axis.dot(a), pb = axis.dot(b), pc = axis.dot(c);
    const double r = half * axis.cwiseAbs().sum();
    return std::min({pa, pb, pc}) > r || std::max({pa, pb, pc}) < -r;
  };
  for (int i = 0; i < 3; ++i)
    if (separated(Eigen::Vector3d::Unit(i))) return false;
  if (separated((b - a).cross(c - a))) return false;
  const Eigen::Vector3d edges[3] = {b - a, c - b, a - c};
  for (const Eigen::Vector3d& e : edges)
    for (int i = 0; i < 3; ++i)
      if (separated(Eigen::Vector3d::Unit(i).cross(e))) return false;
  return true;
}

struct VoxelGrid {
  Eigen::Vector3d origin;
  double size;
  Eigen::Vector3i dims;
};

VoxelGrid grid_around(const Mesh& mesh, double size, int margin) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (const Eigen::Vector3d& v : mesh.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  VoxelGrid g;
  g.size = size;
  for (int a = 0; a < 3; ++a) {
    const double cells = (hi[a] - lo[a]) / size;
    if (cells > 4096)
      throw Error("voxel size " + std::to_string(size) +
                  " is too small for the part (more than 4096 voxels along an axis)");
    g.dims[a] = static_cast<int>(std::ceil(cells)) + 1 + 2 * margin;
    g.origin[a] = 0.5 * (lo[a] + hi[a]) - 0.5 * (g.dims[a] - 1) * size;
  }
  return g;
}

// Calls visit(triangle index, i, j, k) for every voxel that triangle overlaps.
template <typename Visit>
void for_each_overlapped_voxel(const Mesh& mesh, const VoxelGrid& g, Visit visit) {
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Eigen::Vector3d& v0 = mesh.vertices[mesh.triangles[t][0]];
    const Eigen::Vector3d& v1 = mesh.vertices[mesh.triangles[t][1]];
    const Eigen::Vector3d& v2 = mesh.vertices[mesh.triangles[t][2]];
    Eigen::Vector3i lo, hi;
    for (int a = 0; a < 3; ++a) {
      const double mn = std::min({v0[a], v1[a], v2[a]}), mx = std::max({v0[a], v1[a], v2[a]});
      lo[a] = std::max(0, static_cast<int>(std::floor((mn - g.origin[a]) / g.size + 0.5)) - 1);
      hi[a] = std::min(g.dims[a] - 1, static_cast<int>(std::floor((mx - g.origin[a]) / g.size + 0.5)) + 1);
    }
    for (int k = lo.z(); k <= hi.z(); ++k)
      for (int j = lo.y(); j <= hi.y(); ++j)
        for (int i = lo.x(); i <= hi.x(); ++i)
          if (triangle_overlaps_box(g.origin + g.size * Eigen::Vector3d(i, j, k), 0.5 * g.size, v0, v1, v2))
            visit(t, i, j, k);
  }
}

void check_input(const Mesh& mesh, double size, const char* what) {
  if (mesh.empty()) throw Error(std::string(what) + ": the mesh is empty");
  if (!(std::isfinite(size) && size > 0))
    throw Error(std::string(what) + ": the voxel size must be > 0 (got " + std::to_string(size) + ")");
}

}  // namespace

std::size_t Voxmap::count(VoxelState s) const {
  return static_cast<std::size_t>(std::count(state.begin(), state.end(), s));
}

Voxmap build_voxmap(const Mesh& mesh, double voxel_size, int proximity_layers) {
  check_input(mesh, voxel_size, "voxmap");
  if (proximity_layers < 0 || proximity_layers > 200)
    throw Error("voxmap: proximity layers must be in [0, 200] (got " + std::to_string(proximity_layers) + ")");
  const VoxelGrid g = grid_around(mesh, voxel_size, proximity_layers + 1);
  Voxmap m;
  m.origin = g.origin;
  m.voxel_size = voxel_size;
  m.dims = g.dims;
  m.proximity_layers = proximity_layers;
  const std::size_t n = static_cast<std::size_t>(g.dims.x()) * g.dims.y() * g.dims.z();
  m.state.assign(n, VoxelState::free);
  m.layer.assign(n, 0);
  for_each_overlapped_voxel(mesh, g,
                            [&](std::size_t, int i, int j, int k) { m.state[m.index(i, j, k)] = VoxelState::surface; });

  // Interior: the winding count along a vertical ray through each column, from the
  // signed z crossings of the triangles (entering where the outward normal points down).
  // The ray is nudged off the voxel centres so that it never runs along an edge.
  const double nudge_x = 1.7e-5 * voxel_size, nudge_y = 3.1e-5 * voxel_size;
  std::vector<std::vector<std::pair<double, int>>> crossings(static_cast<std::size_t>(g.dims.x()) * g.dims.y());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    if (normal.z() == 0) continue;
    const int i0 =
        std::max(0, static_cast<int>(std::floor((std::min({a.x(), b.x(), c.x()}) - g.origin.x()) / voxel_size)));
    const int i1 = std::min(g.dims.x() - 1,
                            static_cast<int>(std::ceil((std::max({a.x(), b.x(), c.x()}) - g.origin.x()) / voxel_size)));
    const int j0 =
        std::max(0, static_cast<int>(std::floor((std::min({a.y(), b.y(), c.y()}) - g.origin.y()) / voxel_size)));
    const int j1 = std::min(g.dims.y() - 1,
                            static_cast<int>(std::ceil((std::max({a.y(), b.y(), c.y()}) - g.origin.y()) / voxel_size)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const double x = g.origin.x() + i * voxel_size + nudge_x, y = g.origin.y() + j * voxel_size + nudge_y;
        // 2D barycentric coordinates of (x, y) in the projected triangle.
        const double det = (b.x() - a.x()) * (c.y() - a.y()) - (c.x() - a.x()) * (b.y() - a.y());
        const double u = ((b.x() - x) * (c.y() - y) - (c.x() - x) * (b.y() - y)) / det;
        const double v = ((c.x() - x) * (a.y() - y) - (a.x() - x) * (c.y() - y)) / det;
        const double w = 1 - u - v;
        if (u < 0 || v < 0 || w < 0) continue;
        crossings[static_cast<std::size_t>(i) + static_cast<std::size_t>(g.dims.x()) * j].push_back(
            {u * a.z() + v * b.z() + w * c.z(), normal.z() < 0 ? 1 : -1});
      }
  }
  for (int j = 0; j < g.dims.y(); ++j)
    for (int i = 0; i < g.dims.x(); ++i) {
      auto& column = crossings[static_cast<std::size_t>(i) + static_cast<std::size_t>(g.dims.x()) * j];
      std::sort(column.begin(), column.end());
      std::size_t next = 0;
      int winding = 0;
      for (int k = 0; k < g.dims.z(); ++k) {
        const double z = g.origin.z() + k * voxel_size;
        while (next < column.size() && column[next].first < z) winding += column[next++].second;
        VoxelState& s = m.state[m.index(i, j, k)];
        if (winding > 0 && s == VoxelState::free) s = VoxelState::interior;
      }
    }

  // Distance layers by breadth-first search from the surface voxels (26-neighbourhood):
  // inwards through the interior, outwards through free space up to proximity_layers.
  std::deque<Eigen::Vector3i> queue;
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i)
        if (m.state[m.index(i, j, k)] == VoxelState::surface) queue.push_back({i, j, k});
  while (!queue.empty()) {
    const Eigen::Vector3i v = queue.front();
    queue.pop_front();
    const VoxelState from = m.state[m.index(v.x(), v.y(), v.z())];
    const int layer = m.layer[m.index(v.x(), v.y(), v.z())];
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const Eigen::Vector3i u = v + Eigen::Vector3i(dx, dy, dz);
          if ((u.array() < 0).any() || (u.array() >= g.dims.array()).any()) continue;
          const std::size_t id = m.index(u.x(), u.y(), u.z());
          if (m.layer[id] != 0 || m.state[id] == VoxelState::surface) continue;
          const bool inward = m.state[id] == VoxelState::interior && from == VoxelState::interior;
          const bool outward = m.state[id] == VoxelState::free && from != VoxelState::interior;
          const bool first_in = m.state[id] == VoxelState::interior && from == VoxelState::surface;
          if (!inward && !outward && !first_in) continue;
          if (outward && layer < proximity_layers) m.state[id] = VoxelState::proximity;
          m.layer[id] = static_cast<std::uint8_t>(std::min(255, layer + 1));
          queue.push_back(u);
        }
  }
  return m;
}

PointShell build_point_shell(const Mesh& mesh, double spacing) {
  check_input(mesh, spacing, "point shell");
  const VoxelGrid g = grid_around(mesh, spacing, 1);
  const std::size_t n = static_cast<std::size_t>(g.dims.x()) * g.dims.y() * g.dims.z();
  std::vector<double> best(n, std::numeric_limits<double>::infinity());
  std::vector<std::pair<Eigen::Vector3d, std::size_t>> closest(n);
  for_each_overlapped_voxel(mesh, g, [&](std::size_t t, int i, int j, int k) {
    const std::size_t id = static_cast<std::size_t>(i) +
                           static_cast<std::size_t>(g.dims.x()) * (j + static_cast<std::size_t>(g.dims.y()) * k);
    const Eigen::Vector3d centre = g.origin + spacing * Eigen::Vector3d(i, j, k);
    const Eigen::Vector3i& tri = mesh.triangles[t];
    const Eigen::Vector3d q =
        closest_point_on_triangle(centre, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    const double d = (q - centre).squaredNorm();
    if (d < best[id]) best[id] = d, closest[id] = {q, t};
  });
  PointShell shell;
  shell.spacing = spacing;
  constexpr int kChunk = 8;  // voxels per chunk along each axis
  for (int ck = 0; ck < g.dims.z(); ck += kChunk)
    for (int cj = 0; cj < g.dims.y(); cj += kChunk)
      for (int ci = 0; ci < g.dims.x(); ci += kChunk) {
        ShellChunk chunk;
        chunk.begin = shell.points.size();
        for (int k = ck; k < std::min(ck + kChunk, g.dims.z()); ++k)
          for (int j = cj; j < std::min(cj + kChunk, g.dims.y()); ++j)
            for (int i = ci; i < std::min(ci + kChunk, g.dims.x()); ++i) {
              const std::size_t id = static_cast<std::size_t>(i) + static_cast<std::size_t>(g.dims.x()) *
                                                                       (j + static_cast<std::size_t>(g.dims.y()) * k);
              if (!std::isfinite(best[id])) continue;
              const Eigen::Vector3i& tri = mesh.triangles[closest[id].second];
              const Eigen::Vector3d normal =
                  (mesh.vertices[tri[1]] - mesh.vertices[tri[0]]).cross(mesh.vertices[tri[2]] - mesh.vertices[tri[0]]);
              if (!(normal.norm() > 0)) continue;  // a degenerate triangle has no normal to give
              shell.points.push_back(closest[id].first);
              shell.normals.push_back(-normal.normalized());
              shell.radius = std::max(shell.radius, closest[id].first.norm());
            }
        chunk.end = shell.points.size();
        if (chunk.end == chunk.begin) continue;
        for (std::size_t p = chunk.begin; p < chunk.end; ++p) chunk.centre += shell.points[p];
        chunk.centre /= double(chunk.end - chunk.begin);
        for (std::size_t p = chunk.begin; p < chunk.end; ++p)
          chunk.radius = std::max(chunk.radius, (shell.points[p] - chunk.centre).norm());
        shell.chunks.push_back(chunk);
      }
  if (shell.points.empty()) throw Error("point shell: no surface points (degenerate mesh)");
  return shell;
}

}  // namespace snapfit
