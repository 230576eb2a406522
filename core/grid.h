#pragma once
// A uniform grid of sample points: p(i,j,k) = origin + spacing * (i, j, k), with
// i fastest in memory (index = i + dims.x * (j + dims.y * k)), as VTK image data.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

#include "snapfit/grid.h"
#include "snapfit/scene.h"

namespace snapfit {

// The grid that covers `box` grown by `params.padding` on every side, with
// params.spacing, or with params.resolution points along the longest padded axis.
// Throws snapfit::Error for an empty box or a grid of more than 2^31 points.
GridSpec make_grid(const Eigen::AlignedBox3d& box, const GridParams& params);

}  // namespace snapfit

namespace snapfit {

// One spacing for all parts of a scene (their spectra must share it): params.spacing,
// or the longest padded extent over all boxes divided by (resolution - 1).
double common_spacing(const GridParams& params, const std::vector<Eigen::AlignedBox3d>& boxes);

// The grid's point indices in packets of `lanes` (1, 4, 8 or 16) neighbours: bricks of
// 1x1x1, 2x2x1, 2x2x2 or 4x2x2 points, brick after brick in grid order, the points of a
// brick in grid order. Bricks cut by the grid's far faces are padded with -1, so the
// list's length is a multiple of `lanes`. Throws snapfit::Error for another lane count.
std::vector<long long> brick_point_order(const GridSpec& grid, int lanes);

}  // namespace snapfit
