#pragma once
// The Voxmap PointShell - geometric constraint hybrid (seed 002 chapter 5): VPS detects
// the contacts (scheduler/vps/vps_method.h); part 1's surface voxels and part 2's shell points
// carry the analytic faces they lie on (mesh/analytic_faces.h), so each contact names a
// face pair; a compatible pair (scheduler/vps/constraint_recognition.h) is recognised as a
// constraint and phased in. Per engaged constraint k with engagement x_k (eq. 15-17):
//     F = F_other + sum_k [ F_C,k (1 - x_k) + F_A,k x_k ]          (eq. 13, 19)
// (x_k in the blend is min(1, x_k / x_full), HybridParams: x_full = 1 is the paper's)
// and the same for the torque (eq. 14), with F_C,k the collision force of the contacts
// between the constraint's two faces (its region), F_other that of all other contacts
// (edges, unlabelled voxels and points, other pairs: they stay, seed 002 Fig. 25) and
// F_A,k the alignment spring (eq. 18). Torques are about part 2's origin, as in VPS.
//
// Engagement has hysteresis so that it does not chatter: a recognised constraint engages
// when x >= x_engage and releases when x < x_release (or a concentric pair no longer
// overlaps); its weight is ramped in and out over `ramp_s` (the "capacity or filter to
// smoothen out [the] scale factor" of seed 002 5.4), so the wrench changes by a bounded
// step per frame. The alignment stiffnesses are a fraction < 1 of the coupling's: the
// user stays stronger than the constraint (seed 002 5.4).
#include <array>
#include <cstdint>
#include <vector>

#include "mesh/analytic_faces.h"
#include "scheduler/vps/constraint_recognition.h"
#include "scheduler/vps/vps_method.h"
#include "snapfit/scene.h"

namespace snapfit {

struct HybridParams {
  RecognitionTolerance tolerance;  // set from the voxel size by hybrid_model unless > 0
  // Defaults as the scene's (VpsHybridParams): the paper's is rotation_fraction 0.5,
  // x_full 1, region pair; these insert at zero clearance (docs/haptics.md).
  double alignment_fraction = 0.5;  // k_A as this fraction of the coupling's k_T
  double rotation_fraction = 0.9;   // k_R as this fraction of the coupling's k_R
  double x_engage = 0.75;           // engage at x >= this (theta = 0: |d| <= s ln 2)
  double x_release = 0.6;           // release at x < this (theta = 0: |d| > s ln 5)
  // The blend weight is min(1, x / x_full) (times the ramp): 1 is eq. 13's x itself;
  // below 1 the weight saturates once x reaches x_full, so a constraint that is nearly
  // met (x ~ 0.9 deep in a hole, where theta_0 = s / l of eq. 16 is small) blends the
  // region's collision force out entirely.
  double x_full = 0.8;
  double ramp_s = 0.05;                      // seconds to phase a constraint fully in or out
  HybridRegion region = HybridRegion::face;  // which contacts a constraint's region holds
};

// The scene's `vps.hybrid` section as HybridParams (tolerances left to the voxel size
// where the scene gives none).
HybridParams hybrid_params_for(const Scene& scene);

struct HybridModel {
  VpsModel vps;
  std::vector<AnalyticFace> faces1, faces2;  // each part's faces in its own frame
  std::vector<std::int16_t> voxel_face;      // per voxel of vps.voxmap (label_voxmap)
  std::vector<std::int16_t> point_face;      // per point of vps.shell (label_point_shell)
  HybridParams params;
  double k_a_n_per_m = 0;     // alignment stiffness, N / m
  double k_r_nm_per_rad = 0;  // alignment rotational stiffness, N m / rad
};

// The hybrid over a VPS model: labels part 1's surface voxels and part 2's shell points
// with their faces; recognition tolerances from the voxel size s (radius and offset 2 s,
// angle 0.2 rad) unless `params` sets them (> 0); k_A, k_R the fractions of the coupling's.
// Throws snapfit::Error for a fraction outside (0, 1), thresholds not 0 < x_release <
// x_engage <= 1, x_full outside (0, 1], or a negative ramp.
HybridModel hybrid_model(VpsModel vps, std::vector<AnalyticFace> faces1, std::vector<AnalyticFace> faces2,
                         const CouplingParams& coupling, HybridParams params = {});

constexpr int kMaxConstraints = 4;

struct ActiveConstraint {
  ConstraintKind kind = ConstraintKind::none;  // none: a free slot
  std::int16_t face1 = kNoFace, face2 = kNoFace;
  double x = 0;      // eq. 15 this frame
  double phase = 0;  // ramp weight in [0, 1]; the blend uses phase * x
  bool releasing = false;
};

// What the hybrid carries from frame to frame; sized once by hybrid_state_for, so a
// frame allocates nothing.
struct HybridState {
  std::array<ActiveConstraint, kMaxConstraints> active{};
  std::vector<std::uint32_t> pair_contacts;           // this frame's contacts per face pair (faces1 x faces2)
  std::array<QueryWrench, kMaxConstraints> region{};  // this frame's F_C,k, tau_C,k
};
HybridState hybrid_state_for(const HybridModel& model);

struct HybridResult {
  VpsResult vps;                               // vps.query: the blended wrench the loop renders
  QueryWrench collision;                       // the plain VPS wrench (contacts and braking), for comparison
  ConstraintKind kind = ConstraintKind::none;  // the engaged constraint of largest weight
  double x = 0;                                // its blend weight, phase * x
  int engaged = 0;                             // constraints with a weight > 0
};

// One frame: advances `state` (recognition, hysteresis, ramps) by the loop's period.
HybridResult hybrid_wrench(const HybridModel& model, HybridState& state, const BodyState& part);

// The loop's view; neither may outlive it. evaluate_state runs one hybrid frame (the
// loop calls it once a frame) and tags the query with the engaged constraint and its
// weight; evaluate (warm-up and timing queries) is plain VPS and leaves `state` alone.
WrenchEvaluator hybrid_evaluator(const HybridModel& model, HybridState& state);

}  // namespace snapfit
