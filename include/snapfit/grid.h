#pragma once
// A uniform grid of sample points: p(i,j,k) = origin + spacing * (i, j, k), with
// i fastest in memory (index = i + dims.x * (j + dims.y * k)), as VTK image data.
// Fields, maps and their exports (include/snapfit/export.h) are sampled on one.
#include <Eigen/Core>
#include <cstddef>

namespace snapfit {

struct GridSpec {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();
  double spacing = 1.0;
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();

  std::size_t count() const {
    return static_cast<std::size_t>(dims.x()) * static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(dims.z());
  }
  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims.x()) *
               (static_cast<std::size_t>(j) + static_cast<std::size_t>(dims.y()) * static_cast<std::size_t>(k));
  }
  Eigen::Vector3d point(int i, int j, int k) const { return origin + spacing * Eigen::Vector3d(i, j, k); }
  // The point of grid index `id` (the inverse of index()).
  Eigen::Vector3d point(std::size_t id) const {
    const std::size_t nx = static_cast<std::size_t>(dims.x()), ny = static_cast<std::size_t>(dims.y());
    return point(static_cast<int>(id % nx), static_cast<int>(id / nx % ny), static_cast<int>(id / (nx * ny)));
  }
};

// The grid index along `axis` nearest to world coordinate `coordinate`. Throws
// snapfit::Error when it lies outside the grid ("z=12.5 is outside the grid, which
// spans z in [0, 10]") or the axis is not 'x', 'y' or 'z'.
int slice_index_for(const GridSpec& grid, char axis, double coordinate);

// The field `values` (grid.count() floats, grid order) at `p` by trilinear interpolation of
// the 8 surrounding points; `outside` where p is not inside the grid's box or not finite.
double sample_trilinear(const GridSpec& grid, const float* values, const Eigen::Vector3d& p, double outside);

}  // namespace snapfit
