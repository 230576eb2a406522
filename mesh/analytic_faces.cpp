#include "mesh/analytic_faces.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "snapfit/error.h"

namespace snapfit {

namespace {

// Distance in the (axial, radial) half-plane from (a, r) to the segment (a0, r0) - (a1, r1).
double profile_distance(const AnalyticFace& f, double a, double r) {
  const Eigen::Vector2d p0(f.a0, f.r0), p1(f.a1, f.r1), q(a, r);
  const Eigen::Vector2d d = p1 - p0;
  const double len2 = d.squaredNorm();
  const double t = len2 > 0 ? std::clamp((q - p0).dot(d) / len2, 0.0, 1.0) : 0.0;
  return (q - (p0 + t * d)).norm();
}

// Distance in the (axial, radial) half-plane from (a, r) to the shorter arc about (ac, rc)
// from (a0, r0) to (a1, r1): to the circle where the direction from the centre lies
// between the ends', else to the nearer end.
double arc_distance(const AnalyticFace& f, double a, double r) {
  const Eigen::Vector2d c(f.ac, f.rc), p0(f.a0, f.r0), p1(f.a1, f.r1), q(a, r);
  const Eigen::Vector2d u0 = p0 - c, u1 = p1 - c, v = q - c;
  const auto cross = [](const Eigen::Vector2d& x, const Eigen::Vector2d& y) { return x.x() * y.y() - x.y() * y.x(); };
  const double turn = cross(u0, u1);
  const bool between = turn >= 0 ? cross(u0, v) >= 0 && cross(v, u1) >= 0 : cross(u0, v) <= 0 && cross(v, u1) <= 0;
  if (between && v.dot(u0 + u1) > 0) return std::abs(v.norm() - 0.5 * (u0.norm() + u1.norm()));
  return std::min((q - p0).norm(), (q - p1).norm());
}

}  // namespace

double face_distance(const AnalyticFace& f, const Eigen::Vector3d& p) {
  const Eigen::Vector3d rel = p - f.origin;
  const double h = rel.dot(f.axis);
  if (f.kind == FaceKind::plane) {
    // Height above the plane, combined with how far the foot lies outside the extent.
    const Eigen::Vector3d foot = p - h * f.axis;
    const double box = (f.lo - foot).cwiseMax(foot - f.hi).cwiseMax(0.0).norm();
    const double rho = (foot - f.origin).norm();
    double radial = std::max({f.r_in - rho, rho - f.r_out, 0.0});
    for (const ExcludedDisc& hole : f.holes) radial = std::max(radial, hole.radius - (foot - hole.centre).norm());
    const double out = std::max(box, radial);
    return std::sqrt(h * h + out * out);
  }
  const double rho = (rel - h * f.axis).norm();
  return f.kind == FaceKind::torus ? arc_distance(f, h, rho) : profile_distance(f, h, rho);
}

AnalyticFace rotated_face(const AnalyticFace& face, const Eigen::Matrix3d& rotation) {
  AnalyticFace f = face;
  f.origin = rotation * face.origin;
  f.axis = rotation * face.axis;
  for (ExcludedDisc& hole : f.holes) hole.centre = rotation * hole.centre;
  if (face.kind == FaceKind::plane) {
    // Each coordinate of the turned box's corners: the infinite ones stay infinite.
    for (int a = 0; a < 3; ++a) {
      double lo = 0, hi = 0;
      for (int b = 0; b < 3; ++b) {
        const double r = rotation(a, b);
        if (r == 0) continue;
        const double u = r * face.lo[b], v = r * face.hi[b];
        lo += std::min(u, v);
        hi += std::max(u, v);
      }
      f.lo[a] = lo;
      f.hi[a] = hi;
    }
  }
  return f;
}

std::int16_t face_at(const std::vector<AnalyticFace>& faces, const Eigen::Vector3d& p, double tolerance,
                     double edge_band) {
  if (faces.size() > 32767)
    throw Error("analytic faces: at most 32767 faces (got " + std::to_string(faces.size()) + ")");
  if (!(tolerance > 0) || !(edge_band > 0))
    throw Error("analytic faces: the tolerance and edge band must be > 0 (got " + std::to_string(tolerance) + ", " +
                std::to_string(edge_band) + ")");
  double best = std::numeric_limits<double>::infinity(), second = best;
  std::int16_t id = kNoFace;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const double d = face_distance(faces[i], p);
    if (d < best) {
      second = best;
      best = d;
      id = static_cast<std::int16_t>(i);
    } else if (d < second) {
      second = d;
    }
  }
  if (!(best <= tolerance)) return kNoFace;
  if (faces[id].kind == FaceKind::torus) return kNoFace;  // a fillet: no constraint reads it
  if (second <= edge_band) return kEdge;
  return id;
}

}  // namespace snapfit
