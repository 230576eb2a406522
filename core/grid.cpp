#include "core/grid.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "snapfit/error.h"

namespace snapfit {

GridSpec make_grid(const Eigen::AlignedBox3d& box, const GridParams& params) {
  if (box.isEmpty() || !box.min().allFinite() || !box.max().allFinite())
    throw Error("cannot make a grid around an empty or non-finite box");
  const Eigen::Vector3d lo = box.min().array() - params.padding;
  const Eigen::Vector3d extent = (box.max() - box.min()).array() + 2.0 * params.padding;
  GridSpec grid;
  if (params.spacing) {
    grid.spacing = *params.spacing;
  } else if (params.resolution) {
    grid.spacing = extent.maxCoeff() / std::max(1, *params.resolution - 1);
  } else {
    throw Error("grid needs a spacing or a resolution");
  }
  if (!(grid.spacing > 0) || !std::isfinite(grid.spacing)) throw Error("grid spacing must be a positive number");
  double total = 1.0;
  for (int a = 0; a < 3; ++a) {
    const double n = std::ceil(extent[a] / grid.spacing - 1e-9) + 1.0;
    total *= n;
    if (total > 2147483647.0)
      throw Error("grid of spacing " + std::to_string(grid.spacing) + " has more than 2^31 points; use a coarser grid");
    grid.dims[a] = static_cast<int>(n);
  }
  // Centre the grid on the padded box (it may overhang by less than one spacing).
  const Eigen::Vector3d span = grid.spacing * (grid.dims.cast<double>().array() - 1.0).matrix();
  grid.origin = lo - 0.5 * (span - extent);
  return grid;
}

}  // namespace snapfit

namespace snapfit {

double common_spacing(const GridParams& params, const std::vector<Eigen::AlignedBox3d>& boxes) {
  if (params.spacing) return *params.spacing;
  if (!params.resolution || *params.resolution < 2) throw Error("grid needs a spacing or a resolution of at least 2");
  double longest = 0;
  for (const auto& box : boxes) longest = std::max(longest, (box.max() - box.min()).maxCoeff() + 2.0 * params.padding);
  return longest / (*params.resolution - 1);
}

}  // namespace snapfit

namespace snapfit {

std::vector<long long> brick_point_order(const GridSpec& grid, int lanes) {
  Eigen::Vector3i brick;
  switch (lanes) {
    case 1:
      brick = {1, 1, 1};
      break;
    case 4:
      brick = {2, 2, 1};
      break;
    case 8:
      brick = {2, 2, 2};
      break;
    case 16:
      brick = {4, 2, 2};
      break;
    default:
      throw Error("point packets of " + std::to_string(lanes) + " lanes: expected 1, 4, 8 or 16");
  }
  const Eigen::Vector3i bricks = (grid.dims + brick - Eigen::Vector3i::Ones()).cwiseQuotient(brick);
  std::vector<long long> order;
  order.reserve(static_cast<std::size_t>(bricks.prod()) * static_cast<std::size_t>(lanes));
  for (int bk = 0; bk < bricks.z(); ++bk)
    for (int bj = 0; bj < bricks.y(); ++bj)
      for (int bi = 0; bi < bricks.x(); ++bi)
        for (int dk = 0; dk < brick.z(); ++dk)
          for (int dj = 0; dj < brick.y(); ++dj)
            for (int di = 0; di < brick.x(); ++di) {
              const int i = bi * brick.x() + di, j = bj * brick.y() + dj, k = bk * brick.z() + dk;
              const bool inside = i < grid.dims.x() && j < grid.dims.y() && k < grid.dims.z();
              order.push_back(inside ? static_cast<long long>(grid.index(i, j, k)) : -1);
            }
  return order;
}

}  // namespace snapfit

namespace snapfit {

double sample_trilinear(const GridSpec& grid, const float* values, const Eigen::Vector3d& p, double outside) {
  const Eigen::Vector3d u = (p - grid.origin) / grid.spacing;
  int base[3];
  double f[3];
  for (int a = 0; a < 3; ++a) {
    const int n = grid.dims[a];
    if (!(u[a] >= 0.0 && u[a] <= n - 1)) return outside;
    base[a] = std::min(static_cast<int>(u[a]), std::max(n - 2, 0));
    f[a] = n > 1 ? u[a] - base[a] : 0.0;
  }
  double sum = 0;
  for (int c = 0; c < 8; ++c) {
    const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
    const double w = (di ? f[0] : 1 - f[0]) * (dj ? f[1] : 1 - f[1]) * (dk ? f[2] : 1 - f[2]);
    if (w == 0) continue;
    sum += w * values[grid.index(base[0] + di, base[1] + dj, base[2] + dk)];
  }
  return sum;
}

}  // namespace snapfit
