#include "mesh/mesh_distance.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace snapfit {

Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c) {
  // Voronoi regions of the vertices, then edges, then the face (Ericson 5.1.5).
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

double winding_number(const Mesh& mesh, const Eigen::Vector3d& p) {
  double total = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]] - p, b = mesh.vertices[t[1]] - p, c = mesh.vertices[t[2]] - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    const double numerator = a.dot(b.cross(c));
    const double denominator = la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb;
    total += 2.0 * std::atan2(numerator, denominator);
  }
  return total / (4.0 * M_PI);
}

double signed_distance(const Mesh& mesh, const Eigen::Vector3d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const Eigen::Vector3i& t : mesh.triangles)
    best =
        std::min(best, (closest_point_on_triangle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]) - p)
                           .squaredNorm());
  const double d = std::sqrt(best);
  return winding_number(mesh, p) > 0.5 ? -d : d;
}

MeshDistanceIndex::MeshDistanceIndex(const Mesh& mesh) : mesh_(mesh) {
  lo_ = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  hi_ = -lo_;
  for (const Eigen::Vector3d& v : mesh.vertices) lo_ = lo_.cwiseMin(v), hi_ = hi_.cwiseMax(v);
  if (mesh.empty()) return;
  // About two triangles per cell of a surface: cells of the size of a typical triangle.
  const Eigen::Vector3d size = (hi_ - lo_).cwiseMax(1e-9);
  double area = 0;
  for (const Eigen::Vector3i& t : mesh.triangles)
    area += 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
  cell_ = std::max(std::sqrt(2 * area / mesh.triangles.size()), size.maxCoeff() / 256);
  for (int a = 0; a < 3; ++a) dims_[a] = std::max(1, static_cast<int>(std::ceil(size[a] / cell_)));
  cells_.resize(static_cast<std::size_t>(dims_.x()) * dims_.y() * dims_.z());
  columns_.resize(static_cast<std::size_t>(dims_.x()) * dims_.y());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    Eigen::Vector3d tlo = mesh.vertices[mesh.triangles[t][0]], thi = tlo;
    for (int k = 1; k < 3; ++k)
      tlo = tlo.cwiseMin(mesh.vertices[mesh.triangles[t][k]]), thi = thi.cwiseMax(mesh.vertices[mesh.triangles[t][k]]);
    const Eigen::Vector3i a = cell_of(tlo), b = cell_of(thi);
    for (int k = a.z(); k <= b.z(); ++k)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int i = a.x(); i <= b.x(); ++i)
          cells_[i + static_cast<std::size_t>(dims_.x()) * (j + static_cast<std::size_t>(dims_.y()) * k)].push_back(
              static_cast<int>(t));
    for (int j = a.y(); j <= b.y(); ++j)
      for (int i = a.x(); i <= b.x(); ++i)
        columns_[i + static_cast<std::size_t>(dims_.x()) * j].push_back(static_cast<int>(t));
  }
}

Eigen::Vector3i MeshDistanceIndex::cell_of(const Eigen::Vector3d& p) const {
  Eigen::Vector3i c;
  for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor((p[a] - lo_[a]) / cell_)), 0, dims_[a] - 1);
  return c;
}

bool MeshDistanceIndex::inside(const Eigen::Vector3d& p) const {
  if (mesh_.empty() || (p.array() < lo_.array()).any() || (p.array() > hi_.array()).any()) return false;
  const double x = p.x() + 1.7e-9 * cell_, y = p.y() + 3.1e-9 * cell_;
  const Eigen::Vector3i c = cell_of(p);
  int winding = 0;
  for (int t : columns_[c.x() + static_cast<std::size_t>(dims_.x()) * c.y()]) {
    const Eigen::Vector3i& tri = mesh_.triangles[t];
    const Eigen::Vector3d &a = mesh_.vertices[tri[0]], &b = mesh_.vertices[tri[1]], &cc = mesh_.vertices[tri[2]];
    const double det = (b.x() - a.x()) * (cc.y() - a.y()) - (cc.x() - a.x()) * (b.y() - a.y());
    if (det == 0) continue;  // vertical: the ray runs along it, not through it
    const double u = ((b.x() - x) * (cc.y() - y) - (cc.x() - x) * (b.y() - y)) / det;
    const double v = ((cc.x() - x) * (a.y() - y) - (a.x() - x) * (cc.y() - y)) / det;
    const double w = 1 - u - v;
    if (u < 0 || v < 0 || w < 0) continue;
    if (u * a.z() + v * b.z() + w * cc.z() <= p.z()) continue;
    winding += det > 0 ? 1 : -1;  // above p: leaving the solid where the normal points up (det > 0)
  }
  return winding > 0;
}

double MeshDistanceIndex::distance(const Eigen::Vector3d& p) const {
  if (mesh_.empty()) return std::numeric_limits<double>::infinity();
  // Shells of cells around p's cell: after shell r, every triangle not yet seen lies
  // outside a box around p at least r cells (minus p's own offset from its cell's
  // faces) away, so the search stops once the best distance is within that.
  const Eigen::Vector3i c = cell_of(p);
  const Eigen::Vector3d q = (p - lo_) / cell_;  // p in cell units (may lie outside the grid)
  // How far p lies outside the mesh's box along each axis, cell units (0 within its span).
  const Eigen::Vector3d outside = ((lo_ - p).cwiseMax(p - hi_) / cell_).cwiseMax(0.0);
  double best2 = std::numeric_limits<double>::infinity();
  const int max_r = dims_.maxCoeff();
  for (int r = 0; r <= max_r; ++r) {
    for (int k = c.z() - r; k <= c.z() + r; ++k)
      for (int j = c.y() - r; j <= c.y() + r; ++j)
        for (int i = c.x() - r; i <= c.x() + r; ++i) {
          if (std::max({std::abs(i - c.x()), std::abs(j - c.y()), std::abs(k - c.z())}) != r) continue;
          if (i < 0 || j < 0 || k < 0 || i >= dims_.x() || j >= dims_.y() || k >= dims_.z()) continue;
          for (int t :
               cells_[i + static_cast<std::size_t>(dims_.x()) * (j + static_cast<std::size_t>(dims_.y()) * k)]) {
            const Eigen::Vector3i& tri = mesh_.triangles[t];
            best2 = std::min(best2, (closest_point_on_triangle(p, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]],
                                                               mesh_.vertices[tri[2]]) -
                                     p)
                                        .squaredNorm());
          }
        }
    // The searched block spans cells c - r .. c + r. A triangle not yet seen lies in the
    // mesh's box and beyond one of the block's inner faces, along axis a: at least that
    // face's gap from p along a, and at least p's distance outside the box along the other
    // axes (which keeps the search short for a point far outside the part's box).
    double reach2 = std::numeric_limits<double>::infinity();
    for (int a = 0; a < 3; ++a) {
      double gap = std::numeric_limits<double>::infinity();
      if (c[a] - r > 0) gap = std::min(gap, q[a] - (c[a] - r));
      if (c[a] + r < dims_[a] - 1) gap = std::min(gap, (c[a] + r + 1) - q[a]);
      if (std::isfinite(gap))
        reach2 = std::min(reach2, gap * gap + outside.squaredNorm() - outside[a] * outside[a]);
    }
    if (std::isfinite(best2) && best2 <= reach2 * cell_ * cell_) break;
  }
  return std::sqrt(best2);
}

double MeshDistanceIndex::signed_distance(const Eigen::Vector3d& p) const {
  const double d = distance(p);
  return inside(p) ? -d : d;
}

}  // namespace snapfit
