#pragma once
// Spherical decomposition of a part, seed 001 Algorithm 1 (Appendix A): balls centred at
// the grid nodes inside the solid, radius = distance to the boundary, chosen greedily in
// descending skeletal density (the "SDF" of seed 001 [3], the engine's s), then expanded
// by epsilon (A.2) and reduced to the balls not engulfed by another expanded ball (A.4).
//
// Two departures from the printed algorithm, both to make the stated properties hold:
// - the protrusion test (A.1) uses d + r' - r <= mu r' (how far B(x', r') protrudes
//   from B(x, r)), which gives the text's limits Q(x; 0) = {x' : B(x', r') inside
//   B(x, r)} and Q(x; 1) = X inside B(x, r); the printed |r - r'| would also pop
//   nodes outside B(x, r) whose balls are larger;
// - the reduction (A.4) visits the balls by decreasing radius and drops one only when
//   an expanded ball that is kept engulfs it, so every ball of A1 stays inside the
//   union of A3 (Proposition 3's S(A1) in S(A3)); dropping against all of A2 could drop
//   both ends of a chain.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "core/grid.h"
#include "engine/fields/descriptors.h"
#include "engine/runtime/compute_context.h"
#include "mesh/mesh.h"
#include "snapfit/spheres.h"

namespace snapfit {

struct SphereDecompositionParams {
  // The Hausdorff bound epsilon of Propositions 1-3 (scene units): the grid spacing is
  // 2 epsilon / sqrt(3), so epsilon is a cell's half diagonal.
  double tolerance = 1.0;
  double protrusion = 0.25;  // mu of (A.1); seed 001 recommends 0.25-0.30
  BallOrder order = BallOrder::skeletal_density;
};

// Algorithm 1 on given fields of G (grid order): a node is inside where winding >= 1/2,
// its radius is -signed_distance, `priority` orders the selection (higher first).
// Throws snapfit::Error when the sizes differ, no node is inside, or mu is outside [0, 1].
SphereDecomposition decompose_into_balls(const GridSpec& grid, const std::vector<float>& winding,
                                         const std::vector<float>& signed_distance, const std::vector<float>& priority,
                                         double epsilon, double protrusion);

// The grid of a decomposition: the mesh's box grown by one spacing, at 2 epsilon / sqrt(3).
GridSpec sphere_grid(const Mesh& mesh, double tolerance);

// Computes the fields on sphere_grid (the scene's descriptor parameters give the skeletal
// density; the kind is ignored) and runs Algorithm 1. Throws snapfit::Error for an empty
// mesh, a tolerance that is not positive and finite, or a grid over 2^31 points.
SphereDecomposition decompose_part(const ComputeContext& ctx, const Mesh& mesh, const DescriptorParams& descriptor,
                                   const SphereDecompositionParams& params, const DescriptorOptions& options = {});

}  // namespace snapfit
