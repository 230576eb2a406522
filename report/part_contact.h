#pragma once
// What report.html shows as contact: the triangles of one part whose centroid lies inside
// the other part at a frame's pose. "Inside" is the other part's generalized winding
// number field (engine/fields/descriptors.h), trilinearly interpolated on its grid, above 1/2,
// so the test is as sharp as that grid: within about one grid spacing of the other
// part's surface it may go either way, and touching surfaces (zero clearance) read as
// inside or outside by a hair.
#include <cstdint>
#include <vector>

#include "snapfit/grid.h"
#include "snapfit/mesh.h"
#include "snapfit/pose.h"

namespace snapfit {

// The other part's winding number field on its grid, in its own frame.
struct PartVolume {
  const GridSpec* grid = nullptr;
  const std::vector<float>* winding = nullptr;
};

// The centroid of every triangle of `mesh`.
std::vector<Eigen::Vector3d> triangle_centroids(const Mesh& mesh);

// One bit a point (bit i % 8 of byte i / 8): point i, placed by `pose` into the other
// part's frame, is inside it. Points outside its grid are outside. Throws snapfit::Error
// when the field does not match its grid.
std::vector<std::uint8_t> points_inside(const std::vector<Eigen::Vector3d>& points, const Pose& pose,
                                        const PartVolume& other);

}  // namespace snapfit
