// The deepest vertex of one placed mesh inside another (mesh/interpenetration.h).
#include "mesh/interpenetration.h"

#include <algorithm>

namespace snapfit {

double deepest_vertex_inside(const Mesh& a, const Pose& pose_a, const MeshDistanceIndex& b_index) {
  double deepest = 0;
  for (const Eigen::Vector3d& v : a.vertices) {
    const Eigen::Vector3d p = pose_a.apply(v);
    if ((p.array() < b_index.box_min().array()).any() || (p.array() > b_index.box_max().array()).any()) continue;
    if (b_index.inside(p)) deepest = std::max(deepest, b_index.distance(p));
  }
  return deepest;
}

double deepest_interpenetration(const Pose& pose, const Mesh& m1, const MeshDistanceIndex& i1, const Mesh& m2,
                                const MeshDistanceIndex& i2) {
  return std::max(deepest_vertex_inside(m2, pose, i1), deepest_vertex_inside(m1, pose.inverse(), i2));
}

}  // namespace snapfit
