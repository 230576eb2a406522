#pragma once
// The fine level of a SignedDistanceGrid (mesh/signed_distance_grid.h) as the rigid
// contact reads it for each surface point, with integer arithmetic only: a point is given
// by its fine cell (whole fine spacings from the grid's origin) and its fraction within
// that cell, so a lookup needs no division and no floor. Cells outside the grid or in a
// coarse cell without a fine brick are not covered (node() returns null): the caller
// falls back to sample_signed_distance.
//
// A view holds pointers into its grid: make one per evaluation, not per model.
#include <algorithm>
#include <cstddef>
#include <cstdint>

#include "mesh/signed_distance_grid.h"

namespace snapfit {

class FineDistanceView {
 public:
  explicit FineDistanceView(const SignedDistanceGrid& g)
      : bricks_(g.brick_values.data()),
        step_(g.brick_step),
        brick_of_cell_(g.brick_of_cell.data()),
        brick_nodes_(g.brick_nodes()),
        refine_(g.refine),
        side_(std::size_t(g.refine) + 1),
        coarse_x_(g.dims.x() > 0 ? std::size_t(g.dims.x()) - 1 : 0),
        coarse_xy_(coarse_x_ * (g.dims.y() > 0 ? std::size_t(g.dims.y()) - 1 : 0)) {
    for (int a = 0; a < 3; ++a)
      fine_cells_[a] = g.dims[a] > 1 ? std::uint32_t(g.dims[a] - 1) * std::uint32_t(g.refine) : 0;
    // coarse(i) = i / refine as (i * inverse_) >> 40, exact for 0 <= i < 2^20: the
    // product's error, below i / 2^40, never lifts a fraction (at most 1 - 1/refine) past
    // the next whole number.
    inverse_ = (std::uint64_t(1) << 40) / std::uint64_t(g.refine) + 1;
    for (int a = 0; a < 3; ++a) fine_cells_[a] = std::min(fine_cells_[a], std::uint32_t(1) << 20);
  }

  // The brick node at fine cell (i, j, k)'s lowest corner; null outside the fine level.
  const std::int16_t* node(int i, int j, int k) const {
    if (!on_grid(i, j, k)) return nullptr;
    const int ci = coarse(i), cj = coarse(j), ck = coarse(k);
    const std::int32_t brick = brick_of(ci, cj, ck);
    if (brick < 0) return nullptr;
    const std::size_t sub =
        std::size_t(i - ci * refine_) + side_ * (std::size_t(j - cj * refine_) + side_ * std::size_t(k - ck * refine_));
    return bricks_ + std::size_t(brick) * brick_nodes_ + sub;
  }

  // Whether fine cell (i, j, k) lies in a coarse cell without a brick outside the part:
  // every point in it is more than the band from the surface, outside.
  bool outside_beyond_band(int i, int j, int k) const {
    return on_grid(i, j, k) && brick_of(coarse(i), coarse(j), coarse(k)) == kCoarseOutside;
  }

  // Asks for the cache lines of the cell whose lowest node is `n` (its four rows of two nodes).
  void prefetch(const std::int16_t* n) const {
    const std::size_t sy = side_, sz = side_ * side_;
    __builtin_prefetch(n);
    __builtin_prefetch(n + sy + 1);
    __builtin_prefetch(n + sz);
    __builtin_prefetch(n + sz + sy + 1);
  }

  // The trilinear distance in the cell whose lowest node is `n`, at fraction (x, y, z):
  // interpolated in brick steps, then scaled (as sample_signed_distance, to round-off).
  double value(const std::int16_t* n, double x, double y, double z) const {
    const std::size_t sy = side_, sz = side_ * side_;
    const double c00 = n[0] + (n[1] - n[0]) * x, c10 = n[sy] + (n[sy + 1] - n[sy]) * x;
    const double c01 = n[sz] + (n[sz + 1] - n[sz]) * x, c11 = n[sz + sy] + (n[sz + sy + 1] - n[sz + sy]) * x;
    const double c0 = c00 + (c10 - c00) * y, c1 = c01 + (c11 - c01) * y;
    return step_ * (c0 + (c1 - c0) * z);
  }

  // The values at the cell's corners in brick steps: c[i + 2 j + 4 k] at node (i, j, k) from `n`.
  void corner_steps(const std::int16_t* n, float c[8]) const {
    const std::size_t sy = side_, sz = side_ * side_;
    c[0] = n[0], c[1] = n[1], c[2] = n[sy], c[3] = n[sy + 1];
    c[4] = n[sz], c[5] = n[sz + 1], c[6] = n[sz + sy], c[7] = n[sz + sy + 1];
  }

  // The layout, for a vectorized lookup that repeats node()'s arithmetic.
  const std::int16_t* bricks() const { return bricks_; }
  const std::int32_t* brick_of_cell() const { return brick_of_cell_; }
  int refine() const { return refine_; }
  std::size_t side() const { return side_; }                // nodes along a brick's edge
  std::size_t brick_nodes() const { return brick_nodes_; }  // nodes per brick
  std::size_t coarse_x() const { return coarse_x_; }        // brick_of_cell's stride along y
  std::size_t coarse_xy() const { return coarse_xy_; }      // and along z
  std::uint32_t fine_cells(int axis) const { return fine_cells_[axis]; }

 private:
  bool on_grid(int i, int j, int k) const {
    return std::uint32_t(i) < fine_cells_[0] && std::uint32_t(j) < fine_cells_[1] && std::uint32_t(k) < fine_cells_[2];
  }
  // The coarse cell's entry of brick_of_cell: a brick index, or kCoarseOutside / kCoarseInside.
  std::int32_t brick_of(int ci, int cj, int ck) const {
    return brick_of_cell_[std::size_t(ci) + coarse_x_ * std::size_t(cj) + coarse_xy_ * std::size_t(ck)];
  }
  int coarse(int fine) const { return int((std::uint64_t(std::uint32_t(fine)) * inverse_) >> 40); }

  const std::int16_t* bricks_;
  double step_;
  const std::int32_t* brick_of_cell_;
  std::size_t brick_nodes_;
  int refine_;
  std::uint64_t inverse_;
  std::size_t side_, coarse_x_, coarse_xy_;
  std::uint32_t fine_cells_[3];
};

}  // namespace snapfit
