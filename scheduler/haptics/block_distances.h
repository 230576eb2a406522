#pragma once
// Each point of one block of contact points (mesh/contact_blocks.h) on the other part's
// fine distance level at this frame's pose: the node at its fine cell's lowest corner,
// its fraction in that cell and its trilinear distance. Cells, fractions and distances
// are in double: the energy's change over a small motion may be 1e-5 of itself, below
// single precision's round-off.
//
// Two implementations with the same result (to round-off): portable C++, and one that
// does the arithmetic four points at a time with AVX2, taken when the CPU has AVX2 and FMA.
#include <Eigen/Core>
#include <cstdint>

#include "mesh/contact_blocks.h"
#include "mesh/fine_distance_view.h"
#include "mesh/signed_distance_grid.h"

namespace snapfit {

struct BlockDistances {
  const std::int16_t* node[kMaxBlockPoints];  // null off the fine level
  bool outside[kMaxBlockPoints];              // (no node) outside the part beyond the band: no term
  double fx[kMaxBlockPoints], fy[kMaxBlockPoints], fz[kMaxBlockPoints];  // (node) fraction in the cell
  double phi[kMaxBlockPoints];                // (node) trilinear distance, scene units
};

// Fills `out` for the block whose centre lies at `centre_grid` in the grid's frame, a
// point at offset d from it at centre_grid + to_grid d (`to_fine`: to_grid in fine
// spacings, row-major). False when the centre is far off the grid or not finite: no
// fine cell to find, every point takes sample_signed_distance.
bool block_distances(const ContactBlocks& points, const ShellChunk& block, const double to_fine[9],
                     const Eigen::Vector3d& centre_grid, const SignedDistanceGrid& grid,
                     const FineDistanceView& view, BlockDistances& out);

// The two implementations, for tests; block_distances takes the second where it can.
bool block_distances_portable(const ContactBlocks& points, const ShellChunk& block, const double to_fine[9],
                              const Eigen::Vector3d& centre_grid, const SignedDistanceGrid& grid,
                              const FineDistanceView& view, BlockDistances& out);
bool block_distances_avx2_supported();
bool block_distances_avx2(const ContactBlocks& points, const ShellChunk& block, const double to_fine[9],
                          const Eigen::Vector3d& centre_grid, const SignedDistanceGrid& grid,
                          const FineDistanceView& view, BlockDistances& out);

// floor(x) for |x| < 2^31, inline (std::floor is a library call without SSE4.1).
inline int floor_to_int(double x) {
  const int i = int(x);
  return i - (x < i);
}

}  // namespace snapfit
