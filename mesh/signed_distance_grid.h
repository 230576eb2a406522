#pragma once
// A part's signed distance (negative inside) sampled on a regular grid, exact near the
// surface and coarse away from it, for per-frame contact queries: a point's distance and
// gradient by trilinear interpolation in O(1).
//
// Two levels: coarse nodes (spacing `coarse`) over the part's box grown by a margin, and
// a fine brick (spacing coarse / refine) in each coarse cell whose corners' |d| allow the
// surface within `band` of the cell. Node values are exact point-to-mesh signed distances
// (mesh/mesh_distance.h). Since d is 1-Lipschitz, a cell whose corners all have
// |d| > band + its diagonal holds no point within `band` of the surface, so the fine level
// covers every point that close; farther out the coarse trilinear value is used.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "core/huge_page_allocator.h"
#include "mesh/mesh.h"

namespace snapfit {

struct SignedDistanceGrid {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // coarse node (0, 0, 0)
  double coarse = 1;                                 // coarse spacing, scene units
  int refine = 1;                                    // fine cells per coarse cell along an axis
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();    // coarse nodes per axis
  std::vector<float> coarse_values;                  // x fastest
  // Per coarse cell: the index of its fine brick, or (no brick: the cell lies farther than
  // `band` from the surface, all on one side of it) kCoarseOutside or kCoarseInside.
  std::vector<std::int32_t, HugePageAllocator<std::int32_t>> brick_of_cell;
  // (refine + 1)^3 nodes per brick, x fastest, each node's distance in whole `brick_step`s
  // (brick_value). The array starts on a huge page: with refine 3 a brick (64 nodes) is
  // two whole cache lines, and a fine cell's corners lie in one of them for two of its
  // three z-layers. Both arrays are read at random, per contact point and frame.
  std::vector<std::int16_t, HugePageAllocator<std::int16_t>> brick_values;
  double brick_step = 0;  // scene units per unit of brick_values: kBrickStepsPerSpacing per fine spacing
  Eigen::Vector3d part_min = Eigen::Vector3d::Zero(), part_max = Eigen::Vector3d::Zero();  // the mesh's box
  double band = 0;  // the fine level covers every point within `band` of the surface

  std::size_t bricks() const { return brick_of_cell.empty() ? 0 : brick_values.size() / brick_nodes(); }
  std::size_t brick_nodes() const { return std::size_t(refine + 1) * (refine + 1) * (refine + 1); }
  double fine_spacing() const { return coarse / refine; }
  float brick_value(std::size_t node) const { return float(brick_values[node] * brick_step); }
};

constexpr std::int32_t kCoarseOutside = -1, kCoarseInside = -2;

// A fine node's distance is rounded to 1 / kBrickStepsPerSpacing of a fine spacing (within
// half of that of the exact one) and held within 32 fine spacings, keeping its sign: every
// node of a brick lies within the band and two coarse diagonals of the surface (17 fine
// spacings for the rigid contact's grids).
constexpr double kBrickStepsPerSpacing = 1024;

// Samples `mesh` (closed, outward-oriented) with fine spacing `spacing` (coarse spacing
// `spacing * refine`) and a coarse margin of at least `margin` around its box. Throws
// snapfit::Error for an empty mesh or a spacing, band or margin that is not positive.
// With `keep`, the grid covers only the part of that box within the grown box (a part
// much larger than the region in use); outside the grid the distance is then only a
// lower bound, as everywhere outside.
SignedDistanceGrid build_signed_distance_grid(const Mesh& mesh, double spacing, double band, double margin,
                                              int refine = 4, const Eigen::AlignedBox3d* keep = nullptr);

// The interpolated signed distance at p and its gradient (the trilinear interpolant's,
// in scene units per scene unit). Outside the grid: a lower bound of the distance, the
// distance to the mesh's box, with the gradient pointing away from it.
double sample_signed_distance(const SignedDistanceGrid& grid, const Eigen::Vector3d& p, Eigen::Vector3d* gradient);

// A lower bound of the exact signed distance at p, for a broad phase: the interpolated
// distance less the interpolation's largest error in p's cell (sqrt(3)/2 of the cell's
// spacing: the distance is 1-Lipschitz) and the nodes' rounding (a brick step, and
// single precision's on the coarse level); outside
// the grid, the distance to the mesh's box.
double signed_distance_lower_bound(const SignedDistanceGrid& grid, const Eigen::Vector3d& p);

}  // namespace snapfit
