#include "scheduler/vps/constraint_recognition.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

namespace snapfit {

namespace {

Eigen::Vector3d unit_or_x(const Eigen::Vector3d& v) {
  const double n = v.norm();
  return n > 1e-12 ? Eigen::Vector3d(v / n) : Eigen::Vector3d::UnitX();
}

ConstraintOffset concentric_offset(const AnalyticFace& f1, const AnalyticFace& f2, const Pose& pose) {
  const Eigen::Vector3d a1 = f1.axis, o1 = f1.origin;
  const Eigen::Vector3d a2 = pose.rotation * f2.axis, o2 = pose.apply(f2.origin);
  const double c = a1.dot(a2);
  const Eigen::Vector3d a2s = c < 0 ? Eigen::Vector3d(-a2) : a2;  // axes are lines: the nearer sense
  ConstraintOffset out;
  out.theta = std::atan2(a1.cross(a2).norm(), std::abs(c));
  out.turn_axis = unit_or_x(a2s.cross(a1));
  // Axial overlap of the two faces along part 1's axis: the insertion depth l.
  const double p0 = (o2 + f2.a0 * a2 - o1).dot(a1), p1 = (o2 + f2.a1 * a2 - o1).dot(a1);
  const double lo = std::max(f1.a0, std::min(p0, p1)), hi = std::min(f1.a1, std::max(p0, p1));
  out.depth = std::max(0.0, hi - lo);
  // The point of part 2's axis at the middle of the overlap, pulled onto part 1's axis.
  const double mid = 0.5 * (lo + hi);
  const double t = std::abs(c) > 1e-6 ? (mid - (o2 - o1).dot(a1)) / c : 0.0;
  out.point = o2 + t * a2;
  const Eigen::Vector3d on_axis1 = o1 + a1 * (out.point - o1).dot(a1);
  out.d = on_axis1 - out.point;
  out.play = std::abs(f1.radius() - f2.radius());
  return out;
}

ConstraintOffset planar_offset(const AnalyticFace& f1, const AnalyticFace& f2, const Pose& pose) {
  const Eigen::Vector3d n1 = f1.axis, n2 = pose.rotation * f2.axis;
  ConstraintOffset out;
  out.theta = std::atan2(n1.cross(n2).norm(), -n1.dot(n2));
  out.turn_axis = unit_or_x((-n2).cross(n1));
  out.point = pose.apply(f2.origin);
  out.d = -n1 * (out.point - f1.origin).dot(n1);
  // The face's size stands for the insertion depth of eq. 16.
  const double size = std::min(2 * f2.r_out, (f2.hi - f2.lo).norm());
  out.depth = std::isfinite(size) ? size : 0.0;
  return out;
}

}  // namespace

const char* constraint_name(ConstraintKind kind) {
  switch (kind) {
    case ConstraintKind::concentric:
      return "concentric";
    case ConstraintKind::planar:
      return "planar";
    default:
      return "none";
  }
}

ConstraintKind recognise(const AnalyticFace& f1, const AnalyticFace& f2, const Pose& pose,
                         const RecognitionTolerance& tol) {
  if (f1.kind == FaceKind::cylinder && f2.kind == FaceKind::cylinder) {
    if (f1.material_inside == f2.material_inside) return ConstraintKind::none;  // peg in hole only
    const double dr = std::abs(f1.radius() - f2.radius());
    if (dr > tol.radius) return ConstraintKind::none;
    const ConstraintOffset o = concentric_offset(f1, f2, pose);
    if (o.theta > tol.angle || o.d.norm() > dr + tol.offset) return ConstraintKind::none;
    return ConstraintKind::concentric;
  }
  if (f1.kind == FaceKind::plane && f2.kind == FaceKind::plane) {
    const ConstraintOffset o = planar_offset(f1, f2, pose);
    if (o.theta > tol.angle || o.d.norm() > tol.offset) return ConstraintKind::none;
    return ConstraintKind::planar;
  }
  return ConstraintKind::none;
}

ConstraintOffset constraint_offset(ConstraintKind kind, const AnalyticFace& f1, const AnalyticFace& f2,
                                   const Pose& pose) {
  if (kind == ConstraintKind::concentric) return concentric_offset(f1, f2, pose);
  if (kind == ConstraintKind::planar) return planar_offset(f1, f2, pose);
  return {};
}

double engagement(const ConstraintOffset& o, double voxel_size) {
  const double l = std::max(o.depth, voxel_size);
  const double theta0 = voxel_size / l;  // eq. 16
  const double d0 = voxel_size;          // eq. 17
  const double d = std::max(0.0, o.d.norm() - o.play);
  return 0.5 * std::exp(-o.theta / theta0) + 0.5 * std::exp(-d / d0);  // eq. 15
}

QueryWrench alignment_wrench(const ConstraintOffset& o, const Pose& pose, double k_a, double k_r, double u) {
  QueryWrench w;
  w.force = k_a * u * o.d;  // eq. 18, N
  // Torque in N per scene unit of lever arm: the lever arm's and the rotational spring's
  // (k_r theta in N m, divided by metres per unit).
  w.torque = (o.point - pose.translation).cross(w.force) + (k_r * o.theta / u) * o.turn_axis;
  return w;
}

}  // namespace snapfit
