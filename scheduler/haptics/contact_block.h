#pragma once
// One group of blocks of one part's contact points (mesh/contact_blocks.h) against the
// other part's distance grid, added to the contact's sums (scheduler/haptics/contact_sum.h): the
// broad phase and the per-point work of contact_wrench_share (scheduler/haptics/rigid_contact.h).
//
// Passes over a block: every point's fine cell, fraction and distance in the grid
// (scheduler/haptics/block_distances.h; near a fit most points lie within the band but
// not deeper than the skin); and for those deeper, the energy in double and their
// gradient, wrench and stiffness terms in single precision over arrays of them
// (vectorized), summed per block in single precision and into the contact's sums in
// double. Points off the grid's fine level take sample_signed_distance, but for those in
// a coarse cell that lies wholly outside the part beyond the band (no term: skipped).
#include <Eigen/Core>

#include "mesh/contact_blocks.h"
#include "mesh/fine_distance_view.h"
#include "mesh/signed_distance_grid.h"
#include "scheduler/haptics/contact_sum.h"

namespace snapfit {

// How a point at offset d from its block's centre maps, at this frame's pose:
//   into the grid's frame      centre_grid + to_grid d
//   to its arm about part 2's  centre_arm + to_arm d (part 1's frame)
//   reference point
// and the grid's gradient into part 1's frame, to_world grad phi; its derivatives are
// dphi/dt = sign g, dphi/dtheta = sign arm x g.
struct PointMap {
  Eigen::Matrix3d to_grid, to_arm, to_world;
  double sign = 1;
  double to_fine[9];  // to_grid in fine spacings of the grid, row-major
  // Single-precision forms, row-major: to_arm; and sign to_world times the brick step per
  // fine spacing, taking the fine level's gradient (brick steps per fine spacing) to dphi/dt.
  float to_arm_f[9], to_dphi_dt[9];
};

PointMap point_map(const Eigen::Matrix3d& to_grid, const Eigen::Matrix3d& to_arm, const Eigen::Matrix3d& to_world,
                   double sign, const SignedDistanceGrid& grid);

// The contact's constants: skin (scene units), k_area = k u^2 (N / m per m of depth per
// scene unit^2 of area), u = metres per scene unit.
struct ContactConstants {
  double skin = 0, k_area = 0, metres_per_unit = 1;
};

// Adds the contact of a group of blocks (mesh/contact_blocks.h) of one part's points at
// this frame's pose (`map`; a block centre c lies at map.to_grid c + grid_offset in the
// grid's frame, its arm at map.to_arm c + arm_offset). The group, then each block, is
// skipped when a lower bound of the distance at its centre (as signed_distance_lower_bound;
// in single precision on the fine level) leaves none of its points deeper than the skin:
// a point in a fine cell is interpolated within sqrt(3)/2 fine spacings of its exact
// distance, one in a coarse cell (beyond the band) or off the grid keeps its sign.
void add_group_contact(const ContactBlocks& points, const ShellChunk& group, const PointMap& map,
                       const Eigen::Vector3d& grid_offset, const Eigen::Vector3d& arm_offset,
                       const SignedDistanceGrid& grid, const FineDistanceView& view, const ContactConstants& constants,
                       ContactSum& sum);

}  // namespace snapfit
