#pragma once
// A mesh cut by an axis-aligned plane: the outline a slice image of a field draws over
// it. Coordinates in the plane follow io/png_export.h's slice orientation: for axis 'z'
// (u, v) = (x, y), for 'y' (x, z), for 'x' (y, z).
#include <Eigen/Core>
#include <vector>

#include "mesh/mesh.h"
#include "snapfit/fields.h"

namespace snapfit {

// One segment for every triangle that crosses the plane {p[axis] = value}. A vertex on
// the plane counts as above it, so a crossing is found once and a triangle that only
// touches the plane gives nothing. Throws snapfit::Error for an axis other than 'x',
// 'y', 'z'.
std::vector<OutlineSegment> mesh_slice_outline(const Mesh& mesh, char axis, double value);

}  // namespace snapfit
