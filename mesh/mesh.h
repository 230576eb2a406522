#pragma once
// A part's boundary as one triangle soup, in scene length units.
// Triangles are wound counter-clockwise seen from outside (outward normals), which
// the descriptors rely on for the sign of the winding number and skeletal density.
#include <Eigen/Core>
#include <vector>

namespace snapfit {

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // indices into vertices

  bool empty() const { return triangles.empty(); }
};

}  // namespace snapfit
