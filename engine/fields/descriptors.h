#pragma once
// Shape descriptors of one part on a uniform grid (seed 000 sec. 2.3 and 3.1;
// docs/design.md "Shape descriptors"), computed by the OpenCL kernels
// kernels/unsigned_distance.cl, winding_number.cl and skeletal_density.cl over a
// TriangleBvh of the part's mesh:
//   w    generalized winding number (1 inside, 0 outside; robust on open meshes)
//   xi   signed distance to the boundary, negative inside (w >= 1/2); not for the
//        indicator kind (collision response only), which needs w alone
//   s    skeletal density, seed 000 eq. 2 with the Gaussian-times-inverse-square
//        kernel: s > 0 inside, s < 0 outside (only for DescriptorKind::skeletal_density)
// and a rigorous per-point bound on the quadrature error of w and of s.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/grid.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "mesh/mesh.h"
#include "snapfit/fields.h"
#include "snapfit/scene.h"

namespace snapfit {

struct DescriptorOptions {
  // Points closer to the surface than this fraction of the grid spacing use it as |xi|
  // (so grid points on the surface give finite values, with the sign of w).
  double min_distance_fraction = 1e-3;
  // Before the hierarchy is built, triangles are split until each fits in a ball of
  // this fraction of the grid spacing (mesh/triangle_refine.h); 0 disables it.
  // 0.5 measured as fast as 0.25 in the density pass (the per-point splitting with the
  // second-moment bound is cheap) with a 4x smaller hierarchy to build.
  double refine_fraction = 0.5;
  // The paper's brute-force O(m n) skeletal density (every triangle, adaptive splitting,
  // no hierarchy, no refinement): for benchmarks and cross-checks only.
  bool brute_force_density = false;
  // Also compute xi for the indicator kind (which needs only w): for checks and exports.
  bool indicator_signed_distance = false;
  // On closed meshes, evaluate w only at one seed per region that the surface cannot
  // cross between grid neighbours and copy it to the region (engine/fields/winding_propagation.h);
  // false: the full kernel at every point (for checks). Open meshes always use the full pass.
  bool winding_sign_propagation = true;
  // Grid points per work item of the skeletal density kernel (1, 4, 8 or 16: a brick of
  // neighbours evaluated in SIMD, kernels/skeletal_density.cl); 0: 8 on CPU devices, 1
  // on others. The fields do not depend on it (each point sums the same terms in the
  // same order).
  int density_lanes = 0;
  std::size_t chunk_points = 16384;  // points per kernel launch (progress granularity)
  std::size_t work_group_size = 0;   // 0: let the OpenCL runtime choose
  int bvh_leaf_size = 4;
  ProgramCacheConfig program_cache = default_program_cache();
  // Called with (pass name, 0, grid points) when a pass starts and after each of its
  // chunks with (pass name, points done, grid points);
  // the passes are "distance", "winding number" and "skeletal density", in that order.
  std::function<void(const std::string&, std::uint64_t, std::uint64_t)> progress;
};

// Computes every field the descriptor kind needs. Throws snapfit::Error for an empty
// mesh or grid, or a device failure (naming the device).
DescriptorFields compute_descriptors(const ComputeContext& ctx, const Mesh& mesh, const GridSpec& grid,
                                     const DescriptorParams& params, const DescriptorOptions& options = {});

// The same descriptors at arbitrary points (the part's frame, scene units), computed in
// the grid units of (origin, spacing): at the points of a grid with that origin and
// spacing the values equal compute_descriptors' (w by the full kernel, not by sign
// propagation). The result's grid is a 1-D list of the points (dims (n, 1, 1)); for
// references that evaluate a part at moved or rotated positions.
DescriptorFields descriptors_at_points(const ComputeContext& ctx, const Mesh& mesh,
                                       const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& origin,
                                       double spacing, const DescriptorParams& params,
                                       const DescriptorOptions& options = {});

}  // namespace snapfit
