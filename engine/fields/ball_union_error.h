#pragma once
// How far a union of balls is from the solid it approximates: the volume of the
// symmetric difference, estimated by uniform sampling of a box around both with a 95 %
// Wilson interval, and a sampled Hausdorff distance (the largest distance from a sample
// in one set and not the other to that other set: a lower estimate of d_H, to set
// against the proven bound epsilon of seed 001 Proposition 3). Inclusion in the solid is
// the engine's winding number (w >= 1/2), distance its unsigned distance.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/fields/descriptors.h"
#include "engine/fields/sphere_decomposition.h"
#include "mesh/mesh.h"

namespace snapfit {

struct BallUnionError {
  double volume_error = 0;                             // |S xor U|, scene units^3
  double volume_error_low = 0, volume_error_high = 0;  // 95 % Wilson interval
  double solid_volume = 0;                             // |S| from the mesh (divergence theorem)
  double sample_box_volume = 0;
  double hausdorff_sampled = 0;  // lower estimate of d_H(S, U)
  std::size_t samples = 0, mismatched = 0;
  double seconds = 0;
};

// Lists, for each sample point, whether it lies in the union; a uniform bucket grid over
// the balls keeps it near O(points) for many balls.
std::vector<char> inside_ball_union(const std::vector<Ball>& balls, const std::vector<Eigen::Vector3d>& points);

// Throws snapfit::Error for an empty mesh or ball list, or zero samples.
BallUnionError ball_union_error(const ComputeContext& ctx, const Mesh& mesh, const std::vector<Ball>& balls,
                                std::size_t samples, std::uint64_t seed = 1, const DescriptorOptions& options = {});

}  // namespace snapfit
