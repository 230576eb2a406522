#pragma once
// How deep two placed meshes interpenetrate: the deepest vertex of either inside the
// other, by exact point-to-mesh signed distance (mesh/mesh_distance.h). For benchmarks
// and tests that judge a pose; vertices only, so an edge crossing a face between
// vertices is not seen.
#include "mesh/mesh.h"
#include "mesh/mesh_distance.h"
#include "snapfit/pose.h"

namespace snapfit {

// The deepest vertex of `a`, placed by `pose_a`, inside the closed mesh of `b_index`
// (b at the identity): >= 0, 0 when none is inside.
double deepest_vertex_inside(const Mesh& a, const Pose& pose_a, const MeshDistanceIndex& b_index);

// The deeper of part 2's vertices inside part 1 and part 1's inside part 2, at `pose`
// (part 2 in part 1's frame).
double deepest_interpenetration(const Pose& pose, const Mesh& m1, const MeshDistanceIndex& i1, const Mesh& m2,
                                const MeshDistanceIndex& i2);

}  // namespace snapfit
