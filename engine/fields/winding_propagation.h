#pragma once
// Winding number by sign propagation on closed meshes.
//
// When the mesh's boundary is a cycle (every undirected edge occurs as often as a->b
// as b->a), the triangles form a closed 2-cycle and the generalized winding number w
// (seed 000 sec. 2.3) is an integer, constant on each connected region of space minus
// the surface. Two grid neighbours a, b at spacing h with unsigned distances
// d_a + d_b > h cannot have the surface between them: a surface point q on the segment
// would give d_a + d_b <= |q - a| + |q - b| = h. So w is the same at both. The grid
// graph with those "cannot cross" edges splits into connected components on which w
// is constant; the full kernel (kernels/winding_number.cl) runs at one seed per
// component and its value is copied to the rest. When the seed's bound proves the
// nearest integer (|w - k| + bound < 1/2, less a margin for float rounding), the
// component gets exactly k with bound 0; otherwise the seed's value and bound.
// Open, non-manifold or inconsistently oriented meshes keep the full pass everywhere:
// there w is not piecewise constant.
#include <cstdint>
#include <vector>

#include "core/grid.h"
#include "mesh/mesh.h"

namespace snapfit {

// True when every undirected edge occurs as many times as a->b as b->a among the
// triangles. Vertices with exactly equal coordinates count as one (meshes loaded as
// triangle soups repeat them); edges from a vertex to itself are ignored.
bool mesh_is_closed(const Mesh& mesh);

struct WindingComponents {
  std::vector<std::int32_t> component;  // per grid point: its component
  std::vector<std::int64_t> seeds;      // per component: the grid point farthest from the surface
};

// Components of the grid graph whose edges join axis neighbours a, b with
// distance[a] + distance[b] > spacing + slack (slack covers the float rounding of the
// distances). `distance` holds the unsigned distance at every grid point.
WindingComponents winding_components(const GridSpec& grid, const std::vector<float>& distance, double slack);

// Rounding slack for `winding_components`: a few float steps of the grid's coordinates
// and spacing (the distances are float values of float geometry).
double distance_rounding_slack(const GridSpec& grid, const Mesh& mesh);

// Fills w and its bound at every grid point from the seeds' values
// (seed_winding[c], seed_bound[c] for component c), rounding to the proven integer
// where the bound allows. Returns the number of components whose integer was proven.
std::size_t propagate_winding(const WindingComponents& components, const std::vector<float>& seed_winding,
                              const std::vector<float>& seed_bound, std::vector<float>& winding,
                              std::vector<float>& winding_bound);

}  // namespace snapfit
