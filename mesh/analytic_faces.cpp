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

}  // namespace

double face_distance(const AnalyticFace& f, const Eigen::Vector3d& p) {
  const Eigen::Vector3d rel = p - f.origin;
  const double h = rel.dot(f.axis);
  if (f.kind == FaceKind::plane) {
    // Height above the plane, combined with how far the foot lies outside the extent.
    const Eigen::Vector3d foot = p - h * f.axis;
    const double box = (f.lo - foot).cwiseMax(foot - f.hi).cwiseMax(0.0).norm();
    const double rho = (foot - f.origin).norm();
    const double radial = std::max({f.r_in - rho, rho - f.r_out, 0.0});
    const double out = std::max(box, radial);
    return std::sqrt(h * h + out * out);
  }
  const double rho = (rel - h * f.axis).norm();
  return profile_distance(f, h, rho);
}

std::int16_t face_at(const std::vector<AnalyticFace>& faces, const Eigen::Vector3d& p, double tolerance,
                     double edge_band) {
  if (faces.size() > 32767) throw Error("analytic faces: at most 32767 faces (got " + std::to_string(faces.size()) + ")");
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
  if (second <= edge_band) return kEdge;
  return id;
}

std::vector<std::int16_t> label_voxmap(const Voxmap& map, const std::vector<AnalyticFace>& faces) {
  std::vector<std::int16_t> out(map.state.size(), kNoFace);
  const double s = map.voxel_size;
  for (int k = 0; k < map.dims.z(); ++k)
    for (int j = 0; j < map.dims.y(); ++j)
      for (int i = 0; i < map.dims.x(); ++i) {
        const std::size_t id = map.index(i, j, k);
        if (map.state[id] != VoxelState::surface) continue;
        out[id] = face_at(faces, map.centre(i, j, k), s, 0.5 * s);
      }
  return out;
}

std::vector<std::int16_t> label_point_shell(const PointShell& shell, const std::vector<AnalyticFace>& faces) {
  std::vector<std::int16_t> out(shell.points.size(), kNoFace);
  for (std::size_t i = 0; i < shell.points.size(); ++i)
    out[i] = face_at(faces, shell.points[i], shell.spacing, 0.5 * shell.spacing);
  return out;
}

}  // namespace snapfit
