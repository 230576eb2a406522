#include "scheduler/haptics/block_distances.h"

namespace snapfit {

bool block_distances_portable(const ContactBlocks& points, const ShellChunk& block, const double to_fine[9],
                              const Eigen::Vector3d& centre_grid, const SignedDistanceGrid& grid,
                              const FineDistanceView& shared_view, BlockDistances& out) {
  // The centre in fine spacings from the grid's origin, as a whole cell `base` and a
  // remainder `rest` lifted more than the block's radius above zero: every point's
  // rest + to_fine d is then positive, and its cell found by truncation.
  const double per_spacing = 1 / grid.fine_spacing();
  const Eigen::Vector3d local = (centre_grid - grid.origin) * per_spacing;
  if (!(local.array().abs() < 1e9).all()) return false;
  const int lift = int(block.radius * per_spacing) + 2;
  int base[3];
  double rest[3];
  for (int a = 0; a < 3; ++a) base[a] = floor_to_int(local[a]) - lift, rest[a] = local[a] - base[a];

  // Pass 1: each point's fine cell (relative to base) and fraction in it.
  const std::size_t n = block.end - block.begin;
  const float *x = points.x.data() + block.begin, *y = points.y.data() + block.begin,
              *z = points.z.data() + block.begin;
  const double* m = to_fine;
  int ci[kMaxBlockPoints], cj[kMaxBlockPoints], ck[kMaxBlockPoints];
  for (std::size_t i = 0; i < n; ++i) {
    const double u = rest[0] + m[0] * x[i] + m[1] * y[i] + m[2] * z[i];
    const double v = rest[1] + m[3] * x[i] + m[4] * y[i] + m[5] * z[i];
    const double w = rest[2] + m[6] * x[i] + m[7] * y[i] + m[8] * z[i];
    ci[i] = int(u), cj[i] = int(v), ck[i] = int(w);
    out.fx[i] = u - ci[i], out.fy[i] = v - cj[i], out.fz[i] = w - ck[i];
  }

  const FineDistanceView view = shared_view;  // a local copy: its fields stay in registers
  // Pass 2: each point's cell in the grid's bricks, its corners fetched ahead (the
  // bricks' reads, not the arithmetic, bound the evaluation).
  for (std::size_t i = 0; i < n; ++i) {
    out.node[i] = view.node(base[0] + ci[i], base[1] + cj[i], base[2] + ck[i]);
    if (out.node[i])
      view.prefetch(out.node[i]);
    else
      out.outside[i] = view.outside_beyond_band(base[0] + ci[i], base[1] + cj[i], base[2] + ck[i]);
  }
  // Pass 3: each distance.
  for (std::size_t i = 0; i < n; ++i)
    if (out.node[i]) out.phi[i] = view.value(out.node[i], out.fx[i], out.fy[i], out.fz[i]);
  return true;
}

bool block_distances(const ContactBlocks& points, const ShellChunk& block, const double to_fine[9],
                     const Eigen::Vector3d& centre_grid, const SignedDistanceGrid& grid,
                     const FineDistanceView& view, BlockDistances& out) {
  static const bool avx2 = block_distances_avx2_supported();
  if (avx2) return block_distances_avx2(points, block, to_fine, centre_grid, grid, view, out);
  return block_distances_portable(points, block, to_fine, centre_grid, grid, view, out);
}

}  // namespace snapfit
