#pragma once
// Poses for the benchmarks that query a scene's pair: spread over its trajectory with
// seeded perturbations, and those the engine accepts.
#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <vector>

#include "engine/query/query_engine.h"
#include "scheduler/haptics/trajectory.h"
#include "snapfit/pose.h"
#include "snapfit/scene.h"

namespace snapfit::bench {

// `count` times evenly spread over the scene's trajectory (its initial and assembled poses
// when it has none), each pose shifted by up to +-max_shift per axis and turned by up to
// max_angle_deg about a random axis (seeded); with `rotate` false, R = I and no turn is drawn.
inline std::vector<Pose> trajectory_poses(const Scene& scene, std::size_t count, unsigned seed, double max_shift,
                                          double max_angle_deg, bool rotate = true) {
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
    if (rotate) {
      Eigen::Vector3d axis(u(rng), u(rng), u(rng));
      if (axis.norm() < 1e-6) axis = Eigen::Vector3d::UnitZ();
      const double angle = max_angle_deg * M_PI / 180.0 * std::abs(u(rng));
      p.rotation = (Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())) * p.rotation).normalized();
    } else {
      p.rotation = Eigen::Quaterniond::Identity();
    }
    poses.push_back(p);
  }
  return poses;
}

// The poses `engine` accepts at its current m' (inside its padded box); `rejected` gets the
// number of the others.
inline std::vector<Pose> usable_poses(QueryEngine& engine, const std::vector<Pose>& poses, std::size_t& rejected) {
  const std::vector<QueryResult> results = engine.query_batch(poses);
  std::vector<Pose> out;
  rejected = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (results[i].flags == query_ok)
      out.push_back(poses[i]);
    else
      ++rejected;
  }
  return out;
}

}  // namespace snapfit::bench
