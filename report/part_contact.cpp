#include "report/part_contact.h"

#include "snapfit/error.h"

namespace snapfit {

std::vector<Eigen::Vector3d> triangle_centroids(const Mesh& mesh) {
  std::vector<Eigen::Vector3d> out;
  out.reserve(mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles)
    out.push_back((mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) / 3.0);
  return out;
}

std::vector<std::uint8_t> points_inside(const std::vector<Eigen::Vector3d>& points, const Pose& pose,
                                        const PartVolume& other) {
  if (other.grid == nullptr || other.winding == nullptr || other.winding->size() != other.grid->count())
    throw Error("points_inside: the winding number field does not match its grid");
  std::vector<std::uint8_t> bits((points.size() + 7) / 8, 0);
  for (std::size_t i = 0; i < points.size(); ++i)
    if (sample_trilinear(*other.grid, other.winding->data(), pose.apply(points[i]), 0.0) > 0.5)
      bits[i / 8] |= static_cast<std::uint8_t>(1u << (i % 8));
  return bits;
}

}  // namespace snapfit
