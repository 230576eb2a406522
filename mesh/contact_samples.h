#pragma once
// Points on a part's surface that stand for it in rigid contact (the point shell of
// Barbic & James 2008): each carries the area it represents, and the points are grouped
// in chunks so a query can skip a whole group far from the other part.
//
// Two kinds of point:
//   - face points: the centroids of the surface cut into pieces about `spacing` across
//     (mesh/triangle_refine.h), weighted by the piece's area;
//   - feature points: along every sharp edge (dihedral angle above `sharp_angle_deg`, or
//     an edge with one triangle) at `spacing`, ends included, weighted spacing^2. An edge
//     of one part can cut a face of the other between that part's face points; these
//     points see it.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/shell_chunk.h"

namespace snapfit {

struct ContactSamples {
  std::vector<Eigen::Vector3d> points;  // in the part's frame, grouped by chunk
  std::vector<double> areas;            // scene units^2 each point stands for
  std::vector<ShellChunk> chunks;
  std::size_t face_points = 0, feature_points = 0;
  double spacing = 0;
};

// Face points (unless `features_only`) and feature points of `mesh`. Throws
// snapfit::Error for an empty mesh or a spacing that is not positive.
ContactSamples build_contact_samples(const Mesh& mesh, double spacing, bool features_only, double sharp_angle_deg = 30);

// The samples inside `box` (the part's frame), chunked again. The counts of face and
// feature points are told apart by the area a feature point stands for (spacing^2), so a
// face point of exactly that area counts as a feature point.
ContactSamples samples_inside(const ContactSamples& samples, const Eigen::AlignedBox3d& box);

}  // namespace snapfit
