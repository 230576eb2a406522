#pragma once
// Exact point-to-mesh distances in double, by brute force over the triangles: the
// closest point on a triangle (Ericson, Real-Time Collision Detection, 5.1.5), and the
// signed distance to a closed, outward-oriented mesh, negative inside, with the sign
// from the generalized winding number (Jacobson et al. 2013: the sum of the triangles'
// signed solid angles over 4 pi, by Van Oosterom & Strackee's formula). An independent
// reference for what the methods' own fields say about contact.
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"

namespace snapfit {

// The point of triangle (a, b, c) closest to p.
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

// Generalized winding number of the mesh at p: 1 inside a closed outward mesh, 0 outside.
double winding_number(const Mesh& mesh, const Eigen::Vector3d& p);

// Distance from p to the mesh's surface, negative where winding_number(p) > 1/2.
double signed_distance(const Mesh& mesh, const Eigen::Vector3d& p);

// The same exact signed distance, fast for many queries: the triangles bucketed in a
// uniform grid, searched in growing shells of cells until no nearer triangle can remain;
// inside by the winding count of the vertical ray above p (crossings of the triangles
// over p's column, entering where the outward normal points down), nudged off edges.
// The mesh must be closed.
class MeshDistanceIndex {
 public:
  explicit MeshDistanceIndex(const Mesh& mesh);
  double signed_distance(const Eigen::Vector3d& p) const;
  bool inside(const Eigen::Vector3d& p) const;
  double distance(const Eigen::Vector3d& p) const;
  const Eigen::Vector3d& box_min() const { return lo_; }
  const Eigen::Vector3d& box_max() const { return hi_; }

 private:
  Mesh mesh_;  // a copy: the index may outlive the caller's mesh
  Eigen::Vector3d lo_, hi_;
  double cell_ = 1;
  Eigen::Vector3i dims_;
  std::vector<std::vector<int>> cells_;    // triangles overlapping each cell's box (x fastest)
  std::vector<std::vector<int>> columns_;  // triangles over each (x, y) column
  Eigen::Vector3i cell_of(const Eigen::Vector3d& p) const;
};

}  // namespace snapfit
