#pragma once
// SO(3)'s exponential and logarithm in rotation vectors, and the inverse of its left
// Jacobian, for queries that render an energy to first order in the rotation since a
// reference R0 (the exact product, the near part's background update): with
// R = exp([theta]x) R0, the torque of E0 - T0.theta is J_l(theta)^-T T0.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace snapfit {

// theta with exp([theta]x) = R (|theta| <= pi).
inline Eigen::Vector3d rotation_log(const Eigen::Matrix3d& R) {
  Eigen::Quaterniond q(R);
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  const double s = q.vec().norm();
  if (s < 1e-12) return 2.0 * q.vec();
  return (2.0 * std::atan2(s, q.w()) / s) * q.vec();
}

inline Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// The inverse of SO(3)'s left Jacobian: d log(exp(theta e) exp(v)) / dtheta = J_l(v)^-1 e.
inline Eigen::Matrix3d left_jacobian_inverse(const Eigen::Vector3d& v) {
  const double a = v.norm();
  const Eigen::Matrix3d V = cross_matrix(v);
  const double c =
      a < 1e-4 ? 1.0 / 12.0 + a * a / 720.0 : (1.0 - a * std::sin(a) / (2.0 * (1.0 - std::cos(a)))) / (a * a);
  return Eigen::Matrix3d::Identity() - 0.5 * V + c * V * V;
}

inline Eigen::Matrix3d rotation_exp(const Eigen::Vector3d& v) {
  const double a = v.norm();
  if (a < 1e-15) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(a, v / a).toRotationMatrix();
}

}  // namespace snapfit
