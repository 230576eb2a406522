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

// Lists, for each sample point, whether it lies in the union; a uniform bucket grid over
// the balls keeps it near O(points) for many balls.
std::vector<char> inside_ball_union(const std::vector<Ball>& balls, const std::vector<Eigen::Vector3d>& points);

// Throws snapfit::Error for an empty mesh or ball list, or zero samples.
BallUnionError ball_union_error(const ComputeContext& ctx, const Mesh& mesh, const std::vector<Ball>& balls,
                                std::size_t samples, std::uint64_t seed = 1, const DescriptorOptions& options = {});

}  // namespace snapfit
