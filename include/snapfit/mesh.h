#pragma once
// A part's boundary as one triangle soup, in scene length units, and the small geometry
// the reports draw with it. Triangles are wound counter-clockwise seen from outside
// (outward normals), which the descriptors rely on for the sign of the winding number
// and skeletal density.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "snapfit/fields.h"

namespace snapfit {

struct Mesh {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<Eigen::Vector3i> triangles;  // indices into vertices

  bool empty() const { return triangles.empty(); }
};

// Splits triangles (longest-edge bisection) until every piece fits in a ball of
// `max_radius` around its centroid: the same surface with the same orientation in
// smaller pieces. Throws snapfit::Error when max_radius is not positive or the result
// would exceed `max_triangles`.
Mesh refine_triangles(const Mesh& mesh, double max_radius, std::size_t max_triangles = 20000000);

// The mesh cut by the axis plane {p[axis] = value}: one segment for every triangle that
// crosses it, in the plane's (u, v) coordinates (axis 'z': (x, y), 'y': (x, z), 'x':
// (y, z), as the slice images of include/snapfit/export.h). A vertex on the plane counts
// as above it, so a crossing is found once and a triangle that only touches the plane
// gives nothing. Throws snapfit::Error for an axis other than 'x', 'y', 'z'.
std::vector<OutlineSegment> mesh_slice_outline(const Mesh& mesh, char axis, double value);

}  // namespace snapfit
