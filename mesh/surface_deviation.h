#pragma once
// How far a rigid part's surface moves between two poses: the two-sided Hausdorff
// distance between the surface placed at pose A and the same surface placed at pose B,
// max(sup_{x on A S} d(x, B S), sup_{y on B S} d(y, A S)), measured over sample points of
// the surface, about one per cell of `spacing` that it crosses (vertices first, so a
// box's corners are exact), with exact point-to-triangle distances (mesh/mesh_distance.h).
//
// It sees geometry, not the pose: a round peg turned about its own axis gives 0 (up to
// its facets' sagitta), a translation by d of a convex part |d|, a small tilt by theta
// about the arm times theta. Sampling can only miss deviation: the true distance is at
// least the measured one, and more by at most the distance from a surface point to the
// nearest sample (a few spacings in the worst case; far less where the deviation
// varies slowly along the surface, as it does under a rigid motion).
//
//   SurfaceDeviationMeter meter(part2_mesh, 0.3);
//   SurfaceDeviation d = meter.between(final_pose, assembled_pose);  // d.distance, d.where
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/mesh_distance.h"
#include "snapfit/pose.h"

namespace snapfit {

struct SurfaceDeviation {
  double distance = 0;  // the two-sided Hausdorff distance over the samples, scene units
  // The sample farthest from the other placement, in the part's own frame, and whether it
  // was placed at pose A (its distance is to the surface at B) or at B.
  Eigen::Vector3d where = Eigen::Vector3d::Zero();
  bool where_at_a = true;
};

class SurfaceDeviationMeter {
 public:
  // Samples `mesh` (in its own frame) about `spacing` apart, or coarser where that would
  // give more than about `max_samples` points (spacing^2 = area / max_samples), and
  // indexes its triangles. Throws snapfit::Error for an empty mesh or a spacing that is
  // not positive.
  SurfaceDeviationMeter(const Mesh& mesh, double spacing, std::size_t max_samples = 100000);

  SurfaceDeviation between(const Pose& a, const Pose& b) const;

  std::size_t samples() const { return points_.size(); }
  double spacing() const { return spacing_; }  // the spacing used

 private:
  std::vector<Eigen::Vector3d> points_;
  MeshDistanceIndex index_;
  double spacing_ = 0;
};

// One measurement: builds the meter, then measures.
SurfaceDeviation surface_deviation(const Mesh& mesh, const Pose& a, const Pose& b, double spacing);

}  // namespace snapfit
