#pragma once
// What the benchmarks that compare with FCL (Debian libfcl-dev) share: a part's BVH model,
// a pose as FCL's transform, and poses spread over a scene's trajectory.
#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "scheduler/trajectory.h"
#include "snapfit/error.h"
#include "snapfit/pose.h"
#include "snapfit/scene.h"

namespace snapfit::bench {

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

// The mesh as an OBBRSS BVH; `seconds` gets the build time.
inline std::shared_ptr<FclModel> fcl_model(const Mesh& m, double& seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<fcl::Vector3d> v(m.vertices.begin(), m.vertices.end());
  std::vector<fcl::Triangle> t;
  t.reserve(m.triangles.size());
  for (const auto& tri : m.triangles) t.emplace_back(std::size_t(tri[0]), std::size_t(tri[1]), std::size_t(tri[2]));
  auto model = std::make_shared<FclModel>();
  if (model->beginModel(int(t.size()), int(v.size())) != fcl::BVH_OK || model->addSubModel(v, t) != fcl::BVH_OK ||
      model->endModel() != fcl::BVH_OK)
    throw Error("FCL: cannot build the BVH model (" + std::to_string(t.size()) + " triangles)");
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return model;
}

inline fcl::Transform3d fcl_transform(const Pose& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = p.rotation.toRotationMatrix();
  tf.translation() = p.translation;
  return tf;
}

// `count` times evenly spread over the scene's trajectory (its initial and assembled poses
// when it has none), each pose shifted by up to +-max_shift per axis and turned by up to
// max_angle_deg about a random axis (seeded).
inline std::vector<Pose> trajectory_poses(const Scene& scene, std::size_t count, unsigned seed, double max_shift,
                                          double max_angle_deg) {
  Trajectory traj = scene.trajectory;
  if (traj.keyframes.empty()) {
    traj.keyframes.push_back({0.0, scene.part2.pose});
    if (scene.assembled_pose) traj.keyframes.push_back({1.0, *scene.assembled_pose});
  }
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double t0 = traj.keyframes.front().time_s, t1 = traj.keyframes.back().time_s;
  std::vector<Pose> poses;
  for (std::size_t i = 0; i < count; ++i) {
    const double t = t0 + (t1 - t0) * (count > 1 ? double(i) / double(count - 1) : 0.0);
    Pose p = trajectory_pose(traj, t);
    p.translation += max_shift * Eigen::Vector3d(u(rng), u(rng), u(rng));
    Eigen::Vector3d axis(u(rng), u(rng), u(rng));
    if (axis.norm() < 1e-6) axis = Eigen::Vector3d::UnitZ();
    const double angle = max_angle_deg * M_PI / 180.0 * std::abs(u(rng));
    p.rotation = (Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())) * p.rotation).normalized();
    poses.push_back(p);
  }
  return poses;
}

}  // namespace snapfit::bench
