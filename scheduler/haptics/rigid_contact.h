#pragma once
// Rigid contact between the two parts' surfaces, rendered beside seed 000's energy so
// that near contact the geometry, not the hand, decides where part 2 goes.
//
// Seed 000's skeletal density vanishes at the surface, so an overlap confined to a thin
// layer of the surface (a peg cutting a rim) costs almost nothing; and its truncated
// energy's minimum need not lie at the fit. This term is the signed-distance / point-shell
// penalty of Barbic & James (2008): each part is a signed distance field
// (mesh/signed_distance_grid.h) and a set of surface points (mesh/contact_samples.h);
// every point of one part at signed distance phi < 0 inside the other adds
//     E_i = 1/2 k A_i (phi + s)^2 for phi < -s   (k: pressure per depth, A_i: the point's area,
//                                             s: a skin of the grid's interpolation error)
// Part 2 contributes all its surface points, part 1 the points of its sharp edges (a
// face of part 1 cannot enter part 2 without points of part 2 entering part 1, but an
// edge can cut between them). The energy is zero wherever the surfaces only touch, so it
// leaves an exact fit where it is, and grows stiff within the first tenths of a millimetre.
//
// Derivatives, with the rotation increment on the left about part 2's origin t (as the
// engine's torque): for a point q of part 2 at p = R q + t, dphi/dt = g, dphi/dtheta =
// (p - t) x g, g = grad phi_1(p); for a point x of part 1, phi = phi_2(R^T (x - t)),
// dphi/dt = -g, dphi/dtheta = -(x - t) x g with g = R grad phi_2. The wrench is
// -dE/d(t, theta), and the stiffness the Gauss-Newton Hessian sum k A_i J_i J_i^T
// (positive semi-definite), which the loop integrates implicitly.
#include <memory>
#include <string>

#include "mesh/contact_blocks.h"
#include "mesh/contact_samples.h"
#include "mesh/mesh.h"
#include "mesh/signed_distance_grid.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/job_facts.h"
#include "snapfit/pose.h"
#include "snapfit/scene.h"

namespace snapfit {

struct RigidContactModel {
  SignedDistanceGrid part1_distance, part2_distance;  // each in its part's frame
  ContactSamples part1_samples;                       // sharp-edge points of part 1
  ContactSamples part2_samples;                       // surface and sharp-edge points of part 2
  // The samples as the per-frame evaluation reads them (prepare_rigid_contact).
  ContactBlocks part1_blocks, part2_blocks;
  double pressure_stiffness = 0;                      // k, N / m^3
  // Contact acts from an interpolated depth of `skin` (scene units) on: the distance
  // grid's interpolation error, so that surfaces that only touch do not push.
  double skin = 0;
  double metres_per_unit = 1e-3;
  bool translation_only = false;  // a translation-only scene: no torque, no rotational stiffness
};

// The model of two meshes: surface samples at `sample_spacing`, distance grids at
// `distance_spacing` (scene units) within `band` of each surface. Throws snapfit::Error
// for bad input. With `part1_region` (part 1's frame), part 1's distance grid and samples
// cover only that box (and the band around it): where part 2 can reach.
RigidContactModel build_rigid_contact(const Mesh& part1, const Mesh& part2, double sample_spacing,
                                      double distance_spacing, double band, double pressure_stiffness_n_per_m3,
                                      double metres_per_unit, const Eigen::AlignedBox3d* part1_region = nullptr);

// Fills the model's point blocks from its samples (build_rigid_contact and the contact
// cache do): needed after changing the samples by hand.
void prepare_rigid_contact(RigidContactModel& model);

// The scene's model (haptics.contact_*): samples at contact_spacing (default the grid
// spacing h), distances at a third of it within two sample spacings of the surface; or
// the geometry comes from the contact cache when it holds it (scheduler/haptics/contact_cache.h);
// null when the scene turns contact off or renders with another method, or when a part
// is not watertight (its inside, and so the sign of its distance, is not defined):
// `why_off`, when given, then says which part and why (empty otherwise). Part 1's
// geometry covers only the region part 2 can reach when the scene bounds it
// (pipeline/reach_region.h scene_region).
std::shared_ptr<const RigidContactModel> rigid_contact_for(const Scene& scene, const Mesh& part1, const Mesh& part2,
                                                           double grid_spacing, std::string* why_off = nullptr);

// The model's facts as a report states them (include/snapfit/job_facts.h): the pressure
// stiffness in N/mm^3, the spacings, the skin and the point counts.
RigidContactFacts rigid_contact_facts(const RigidContactModel& model);

// The contact at part 2's pose `pose` (relative to part 1). No heap allocation.
//
// Evaluated in groups and blocks of nearby points (scheduler/haptics/contact_block.h): a group or
// block whose sphere lies farther from the other part than a lower bound of the distance
// allows is skipped; otherwise its points' distances are interpolated in single
// precision, and only the points deeper than the skin get a gradient and terms. The
// result agrees with the all-double evaluation to single precision's round-off
// (tests/test_contact_precision.cpp). Throws snapfit::Error when the model's point blocks
// do not match its samples (see prepare_rigid_contact).
ContactWrench contact_wrench(const RigidContactModel& model, const Pose& pose);

// One of `shares` disjoint shares of contact_wrench's sum (share in [0, shares)), for
// evaluating it on several threads: the shares' sum (add_contact_share), finished by
// finish_contact, equals contact_wrench. The stiffness holds its lower triangle only.
ContactWrench contact_wrench_share(const RigidContactModel& model, const Pose& pose, std::size_t share,
                                   std::size_t shares);
void add_contact_share(ContactWrench& sum, const ContactWrench& share);
// Fills the stiffness's upper triangle; drops the rotational part when translation-only.
void finish_contact(const RigidContactModel& model, ContactWrench& contact);

}  // namespace snapfit
