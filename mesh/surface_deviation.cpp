#include "mesh/surface_deviation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "mesh/cell_key.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

double surface_area(const Mesh& mesh) {
  double area = 0;
  for (const Eigen::Vector3i& t : mesh.triangles)
    area += 0.5 * (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]).norm();
  return area;
}

// One point per cell of `spacing` that the surface crosses, chosen among candidates at
// most spacing / 2 apart: the triangles' vertices, points along their edges and rows
// across them parallel to their longest edge. A cell keeps a vertex before an edge point
// before a face point (corners, where a turn moves the surface most, stay exact), then
// the candidate nearest its centre. A sliver costs its perimeter / step, not its
// (length / step)^2 as bisection would.
class CellSampler {
 public:
  explicit CellSampler(double spacing) : spacing_(spacing), step_(0.5 * spacing) {}

  void add_triangle(Eigen::Vector3d a, Eigen::Vector3d b, Eigen::Vector3d c) {
    // a-b the longest edge: rows parallel to it are the fewest.
    if ((c - a).squaredNorm() > (b - a).squaredNorm()) std::swap(b, c);
    if ((c - b).squaredNorm() > (b - a).squaredNorm()) std::swap(a, c);
    for (const Eigen::Vector3d* v : {&a, &b, &c}) offer(*v, kVertex);
    segment(a, b, kEdge), segment(b, c, kEdge), segment(c, a, kEdge);
    const double base = (b - a).norm();
    if (!(base > 0)) return;
    const int rows = static_cast<int>(std::ceil((b - a).cross(c - a).norm() / base / step_));
    for (int k = 1; k < rows; ++k) {
      const double t = double(k) / rows;
      const Eigen::Vector3d p = a + t * (c - a), q = b + t * (c - b);
      const int n = std::max(1, static_cast<int>(std::ceil((q - p).norm() / step_)));
      for (int i = 0; i <= n; ++i) offer(p + (q - p) * (double(i) / n), kFace);
    }
  }

  std::vector<Eigen::Vector3d> points() const {
    std::vector<Eigen::Vector3d> out;
    out.reserve(cells_.size());
    for (const auto& [key, kept] : cells_) out.push_back(kept.p);
    std::sort(out.begin(), out.end(), [](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
      return std::lexicographical_compare(u.data(), u.data() + 3, v.data(), v.data() + 3);
    });  // the same order on every run, whatever the hash map's
    return out;
  }

 private:
  enum Rank { kFace = 0, kEdge = 1, kVertex = 2 };
  struct Kept {
    Eigen::Vector3d p;
    int rank;
    double d2;  // squared distance to the cell's centre
  };

  void segment(const Eigen::Vector3d& a, const Eigen::Vector3d& b, Rank rank) {
    const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step_)));
    for (int i = 1; i < n; ++i) offer(a + (b - a) * (double(i) / n), rank);
  }

  void offer(const Eigen::Vector3d& p, Rank rank) {
    Eigen::Vector3d centre;
    const std::uint64_t key = cell_key(p, spacing_, centre);
    const Kept candidate{p, rank, (p - centre).squaredNorm()};
    const auto [it, fresh] = cells_.emplace(key, candidate);
    Kept& kept = it->second;
    if (!fresh && (rank > kept.rank || (rank == kept.rank && candidate.d2 < kept.d2))) kept = candidate;
  }

  double spacing_, step_;
  std::unordered_map<std::uint64_t, Kept> cells_;
};

}  // namespace

SurfaceDeviationMeter::SurfaceDeviationMeter(const Mesh& mesh, double spacing, std::size_t max_samples) : index_(mesh) {
  if (mesh.empty()) throw Error("surface deviation: the mesh has no triangles");
  if (!(std::isfinite(spacing) && spacing > 0)) throw Error("surface deviation: spacing must be > 0");
  spacing_ = std::max(spacing, std::sqrt(surface_area(mesh) / std::max<std::size_t>(max_samples, 1)));
  CellSampler sampler(spacing_);
  for (const Eigen::Vector3i& t : mesh.triangles)
    sampler.add_triangle(mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  points_ = sampler.points();
}

SurfaceDeviation SurfaceDeviationMeter::between(const Pose& a, const Pose& b) const {
  // A sample p placed at A lies at distance d(B^-1 A p, S) from the surface placed at B:
  // both sides are distances to the mesh in its own frame, from one index.
  SurfaceDeviation out;
  out.distance = -1;
  const auto side = [&](const Pose& to_other, bool at_a) {
    for (const Eigen::Vector3d& p : points_) {
      const double d = index_.distance(to_other.apply(p));
      if (d > out.distance) out.distance = d, out.where = p, out.where_at_a = at_a;
    }
  };
  side(b.inverse() * a, true);
  side(a.inverse() * b, false);
  out.distance = std::max(out.distance, 0.0);
  return out;
}

SurfaceDeviation surface_deviation(const Mesh& mesh, const Pose& a, const Pose& b, double spacing) {
  return SurfaceDeviationMeter(mesh, spacing).between(a, b);
}

}  // namespace snapfit
