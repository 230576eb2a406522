#pragma once
// Analytic (B-rep-like) faces of a part and the face a point lies on (face_at), so that
// the Voxmap PointShell - constraint hybrid can name the faces in contact and recognise a
// geometric constraint between them (seed 002 sections 5.2-5.3; the voxels' and shell
// points' labels are in scheduler/vps/face_labels.h).
//
// A face is plain data in the part's own frame:
//   plane     a point on it, its unit normal pointing out of the material, and its
//             extent: a box [lo, hi] (axis-aligned, in the part's frame) that its foot
//             points lie in, a radial range [r_in, r_out] about the point, and discs cut
//             out of it (a disc, an annulus, a rectangle, a square with one or more holes);
//   cylinder  a surface of revolution about an axis (point + unit direction) whose
//   cone      profile is the segment from (a0, r0) to (a1, r1) in (axial, radial)
//             coordinates (r0 == r1 for a cylinder), material on the inside of the
//             radius (a peg) or on the outside (a hole);
//   torus     a fillet: the profile is the shorter circular arc from (a0, r0) to
//             (a1, r1) about (ac, rc). It forms no constraint (seed 002 recognises
//             planes and cylinders): it is listed so that the points on it stay
//             unlabelled instead of taking the plane or cylinder they blend into.
#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <vector>

namespace snapfit {

enum class FaceKind : std::uint8_t { plane, cylinder, cone, torus };

// A disc cut out of a plane face: its centre (on the plane) and radius.
struct ExcludedDisc {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
};

struct AnalyticFace {
  FaceKind kind = FaceKind::plane;
  const char* name = "";                             // static text: "side", "hole wall", ...
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // plane: a point on it; others: on the axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();   // plane: outward unit normal; others: unit axis
  // plane: the in-plane box and the radial range about `origin`
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  Eigen::Vector3d hi = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  double r_in = 0, r_out = std::numeric_limits<double>::infinity();
  std::vector<ExcludedDisc> holes;  // plane: discs not on the face (the holes of a plate)
  // cylinder, cone: the profile segment (a0, r0) - (a1, r1), a along `axis` from `origin`
  double a0 = 0, a1 = 0, r0 = 0, r1 = 0;
  double ac = 0, rc = 0;        // torus: the centre of the profile arc
  bool material_inside = true;  // cylinder, cone: a peg (true) or a hole (false)

  double radius() const { return 0.5 * (r0 + r1); }
};

// Label of a voxel or point that lies on no face within the tolerance, or on an edge:
// within `edge_band` of two faces, so that it belongs to neither constraint.
constexpr std::int16_t kNoFace = -1;
constexpr std::int16_t kEdge = -2;

// Distance from p (part frame) to the face (to its bounded extent, not the whole surface).
double face_distance(const AnalyticFace& face, const Eigen::Vector3d& p);

// The face as seen after turning its part by `rotation` about the part's origin. A plane's
// box becomes the axis-aligned box around the turned one (larger unless the turn maps
// axes onto axes): a bound, as the box is for a face that is not axis-aligned anyway.
AnalyticFace rotated_face(const AnalyticFace& face, const Eigen::Matrix3d& rotation);

// The index of the face nearest p if it lies within `tolerance`; kEdge if a second face
// also lies within `edge_band` (the point sits on the edge between them); kNoFace when
// none is within `tolerance` or the nearest is a torus (a fillet: its points and voxels
// stay unlabelled). Throws snapfit::Error for more than 32767 faces or a
// tolerance or band that is not > 0.
std::int16_t face_at(const std::vector<AnalyticFace>& faces, const Eigen::Vector3d& p, double tolerance,
                     double edge_band);

}  // namespace snapfit
