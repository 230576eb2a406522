// Scripted trajectories (scheduler/haptics/trajectory.h): keyframes reproduced, linear
// positions and slerp rotations in between, held outside, errors.
#include <doctest/doctest.h>

#include "scheduler/haptics/trajectory.h"
#include "snapfit/error.h"

using namespace snapfit;

namespace {

Keyframe key(double t, Eigen::Vector3d p, double degrees_about_z) {
  Keyframe k;
  k.time_s = t;
  k.pose.translation = p;
  k.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(degrees_about_z * M_PI / 180.0, Eigen::Vector3d::UnitZ()));
  return k;
}

}  // namespace

TEST_CASE("trajectory: keyframes, interpolation between them, and holding outside") {
  Trajectory tr;
  tr.keyframes = {key(0.0, {0, 0, 10}, 0), key(1.0, {2, 0, 0}, 90), key(3.0, {2, 4, 0}, 90)};
  CHECK(trajectory_pose(tr, 0.0).translation.isApprox(Eigen::Vector3d(0, 0, 10)));
  CHECK(trajectory_pose(tr, -5.0).translation.isApprox(Eigen::Vector3d(0, 0, 10)));
  CHECK(trajectory_pose(tr, 9.0).translation.isApprox(Eigen::Vector3d(2, 4, 0)));
  const Pose mid = trajectory_pose(tr, 0.5);
  CHECK(mid.translation.isApprox(Eigen::Vector3d(1, 0, 5)));
  // Slerp halfway between 0 and 90 degrees about z is 45 degrees about z.
  const Eigen::AngleAxisd aa(mid.rotation);
  CHECK(aa.angle() == doctest::Approx(M_PI / 4));
  CHECK(std::abs(aa.axis().z()) == doctest::Approx(1.0));
  CHECK(trajectory_pose(tr, 2.0).translation.isApprox(Eigen::Vector3d(2, 2, 0)));
  const std::vector<Pose> poses = sample_trajectory(tr, 10.0);
  CHECK(poses.size() == 31);  // 0.0, 0.1, ..., 3.0
  CHECK(poses.back().translation.isApprox(Eigen::Vector3d(2, 4, 0)));
}

TEST_CASE("trajectory: empty trajectories and bad rates are errors") {
  Trajectory empty;
  CHECK_THROWS_AS(trajectory_pose(empty, 0.0), Error);
  Trajectory tr;
  tr.keyframes = {key(0.0, {0, 0, 0}, 0)};
  CHECK_THROWS_AS(sample_trajectory(tr, 0.0), Error);
  CHECK_THROWS_AS(trajectory_pose(tr, std::nan("")), Error);
  CHECK(sample_trajectory(tr, 100.0).size() == 1);
}
