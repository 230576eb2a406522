#pragma once
// Geometric constraints between the analytic faces of two parts in contact (seed 002
// section 5.3) and how far part 2 is from satisfying one (section 5.4):
//   concentric  a cylinder of part 2 in a cylinder of part 1 (one peg, one hole) of
//               matching radius whose axes are parallel and close within tolerance;
//   planar      a plane of part 2 on a plane of part 1, normals opposed, within tolerance.
// For an engaged constraint: the angular offset theta, the offset vector d (what moves
// part 2 onto the constraint), the insertion depth l, the engagement
//   x = 0.5 exp(-theta / theta_0) + 0.5 exp(-|d| / d_0),  theta_0 = s / l,  d_0 = s  (eq. 15-17)
// and the alignment wrench, a linear spring toward the constraint (eq. 18) with a
// rotational spring toward parallel axes (normals).
#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mesh/analytic_faces.h"
#include "snapfit/pose.h"

namespace snapfit {

enum class ConstraintKind : std::uint8_t { none, concentric, planar };

const char* constraint_name(ConstraintKind kind);  // "none", "concentric", "planar"

struct RecognitionTolerance {
  double radius = 0;  // |r1 - r2| of a concentric pair, scene units
  double offset = 0;  // axis offset beyond |r1 - r2|, or plane separation, scene units
  double angle = 0;   // between the axes, or between one normal and the other's opposite, rad
};

// The constraint that the faces f1 (of part 1, in its frame) and f2 (of part 2, in its
// frame, at `pose` relative to part 1) can form, or none: two cylinders of which one is a
// peg and the other a hole; two planes. Cones and mixed pairs form none.
ConstraintKind recognise(const AnalyticFace& f1, const AnalyticFace& f2, const Pose& pose,
                         const RecognitionTolerance& tolerance);

// Where part 2 stands relative to the constraint `kind` between f1 and f2 (as above), all
// in part 1's frame.
struct ConstraintOffset {
  double theta = 0;                                      // rad
  Eigen::Vector3d d = Eigen::Vector3d::Zero();           // moves `point` onto the constraint
  Eigen::Vector3d point = Eigen::Vector3d::Zero();       // on part 2: where the spring pulls
  Eigen::Vector3d turn_axis = Eigen::Vector3d::UnitX();  // unit: turning part 2 about it reduces theta
  double depth = 0;                                      // l: axial overlap (concentric), face size (planar)
  double play = 0;                                       // |r1 - r2| (concentric): the offset the fit allows
};
ConstraintOffset constraint_offset(ConstraintKind kind, const AnalyticFace& f1, const AnalyticFace& f2,
                                   const Pose& pose);

// Eq. 15-17 with voxel size s; the insertion depth is taken as at least one voxel, and d
// as the offset beyond the play, max(0, |d| - play): a peg anywhere within its hole's
// clearance sits on the constraint (at the paper's low clearances, below a voxel, the same).
double engagement(const ConstraintOffset& offset, double voxel_size);

// A wrench in the units of a QueryResult: force in N, torque in N per scene unit of lever arm.
struct QueryWrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
};

// The alignment wrench on part 2 before blending (eq. 18): F_A = k_A d (N, with d in
// metres), its torque about part 2's origin plus k_R theta about the turn axis, in the
// loop's units (N per scene unit of lever arm).
QueryWrench alignment_wrench(const ConstraintOffset& offset, const Pose& pose, double k_a_n_per_m,
                             double k_r_nm_per_rad, double metres_per_unit);

}  // namespace snapfit
