#include "engine/grid.h"

#include <cmath>
#include <string>

#include "engine/error.h"

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
