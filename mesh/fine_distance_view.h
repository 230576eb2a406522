#pragma once
// The fine level of a SignedDistanceGrid (mesh/signed_distance_grid.h) as the rigid
// contact reads it for each surface point, with integer arithmetic only: a point is given
// by its fine cell (whole fine spacings from the grid's origin) and its fraction within
// that cell, so a lookup needs no division and no floor. Cells outside the grid or in a
// coarse cell without a fine brick are not covered (node() returns null): the caller
// falls back to sample_signed_distance.
//
// A view holds pointers into its grid: make one per evaluation, not per model.
#include <cstddef>
#include <cstdint>

#include "mesh/signed_distance_grid.h"

namespace snapfit {

class FineDistanceView {
 public:
  explicit FineDistanceView(const SignedDistanceGrid& g)
      : bricks_(g.brick_values.data()),
        brick_of_cell_(g.brick_of_cell.data()),
        brick_nodes_(g.brick_nodes()),
        refine_(g.refine),
        side_(std::size_t(g.refine) + 1),
        coarse_x_(g.dims.x() > 0 ? std::size_t(g.dims.x()) - 1 : 0),
        coarse_xy_(coarse_x_ * (g.dims.y() > 0 ? std::size_t(g.dims.y()) - 1 : 0)) {
    for (int a = 0; a < 3; ++a)
      fine_cells_[a] = g.dims[a] > 1 ? std::uint32_t(g.dims[a] - 1) * std::uint32_t(g.refine) : 0;
    shift_ = -1;  // refine a power of two: coarse cell by a shift
    for (int s = 0; s < 5; ++s)
      if (g.refine == 1 << s) shift_ = s;
  }

  // The brick node at fine cell (i, j, k)'s lowest corner; null outside the fine level.
  const float* node(int i, int j, int k) const {
    if (std::uint32_t(i) >= fine_cells_[0] || std::uint32_t(j) >= fine_cells_[1] || std::uint32_t(k) >= fine_cells_[2])
      return nullptr;
    const int ci = coarse(i), cj = coarse(j), ck = coarse(k);
    const std::int32_t brick =
        brick_of_cell_[std::size_t(ci) + coarse_x_ * std::size_t(cj) + coarse_xy_ * std::size_t(ck)];
    if (brick < 0) return nullptr;
    const std::size_t sub =
        std::size_t(i - ci * refine_) + side_ * (std::size_t(j - cj * refine_) + side_ * std::size_t(k - ck * refine_));
    return bricks_ + std::size_t(brick) * brick_nodes_ + sub;
  }

  // Asks for the cache lines of the cell whose lowest node is `n` (its four rows of two nodes).
  void prefetch(const float* n) const {
    const std::size_t sy = side_, sz = side_ * side_;
    __builtin_prefetch(n);
    __builtin_prefetch(n + sy + 1);
    __builtin_prefetch(n + sz);
    __builtin_prefetch(n + sz + sy + 1);
  }

  // The trilinear distance in the cell whose lowest node is `n`, at fraction (x, y, z).
  double value(const float* n, double x, double y, double z) const {
    const std::size_t sy = side_, sz = side_ * side_;
    const double c00 = n[0] + (n[1] - n[0]) * x, c10 = n[sy] + (n[sy + 1] - n[sy]) * x;
    const double c01 = n[sz] + (n[sz + 1] - n[sz]) * x, c11 = n[sz + sy] + (n[sz + sy + 1] - n[sz + sy]) * x;
    const double c0 = c00 + (c10 - c00) * y, c1 = c01 + (c11 - c01) * y;
    return c0 + (c1 - c0) * z;
  }

  // The values at the cell's corners: c[i + 2 j + 4 k] at node (i, j, k) from `n`.
  void corners(const float* n, float c[8]) const {
    const std::size_t sy = side_, sz = side_ * side_;
    c[0] = n[0], c[1] = n[1], c[2] = n[sy], c[3] = n[sy + 1];
    c[4] = n[sz], c[5] = n[sz + 1], c[6] = n[sz + sy], c[7] = n[sz + sy + 1];
  }

 private:
  int coarse(int fine) const { return shift_ >= 0 ? fine >> shift_ : fine / refine_; }

  const float* bricks_;
  const std::int32_t* brick_of_cell_;
  std::size_t brick_nodes_;
  int refine_, shift_;
  std::size_t side_, coarse_x_, coarse_xy_;
  std::uint32_t fine_cells_[3];
};

}  // namespace snapfit
