#pragma once
// A rigid pose (R, t): a point p of a part's own frame maps to R p + t.
// Part 2's pose is always given relative to part 1's frame (docs/design.md: part 1 is the
// frame of reference; rotation about part 2's reference point, then translation).
#include <Eigen/Geometry>

namespace snapfit {

struct Pose {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit quaternion
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d apply(const Eigen::Vector3d& p) const { return rotation * p + translation; }
  Pose inverse() const {
    Pose inv;
    inv.rotation = rotation.conjugate();
    inv.translation = -(inv.rotation * translation);
    return inv;
  }
  // (this * other).apply(p) == this->apply(other.apply(p))
  Pose operator*(const Pose& other) const {
    Pose out;
    out.rotation = rotation * other.rotation;
    out.translation = rotation * other.translation + translation;
    return out;
  }
  bool is_finite() const { return rotation.coeffs().allFinite() && translation.allFinite(); }
};

// How far a pose is from a target: the distance between their translations and the angle
// of the rotation between them.
struct PoseError {
  double position = 0;  // scene units
  double angle_deg = 0;
  bool within(double position_tolerance, double angle_tolerance_deg) const {
    return position <= position_tolerance && angle_deg <= angle_tolerance_deg;
  }
};

PoseError pose_error(const Pose& actual, const Pose& target);

}  // namespace snapfit
