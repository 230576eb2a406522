// The rigid contact's evaluation (scheduler/haptics/rigid_contact.h: point blocks, a broad phase,
// distances in single precision) against a straightforward one written here: every
// sample point of both parts, its distance and gradient by sample_signed_distance in
// double, the terms of the header's formula summed in double. On the shipped scenes at
// poses about their fit: aligned, shifted into a wall or floor by up to a fine spacing,
// tilted, and pushed deeper than the grids' fine band (points the fast path hands to the
// double lookup). They must agree to within what single precision's round-off of a
// distance and a gradient allows, point by point (where a point lies on a grid cell's
// face or at the skin, either side's value is right).
#include <Eigen/Geometry>
#include <doctest/doctest.h>
#include <string>
#include <tuple>
#include <vector>

#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/parallel_contact.h"
#include "scheduler/haptics/rigid_contact.h"
#include "snapfit/error.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

namespace {

// A single-precision distance errs by at most this many fine spacings (the cell
// coordinates' and the interpolation's round-off: about 1e-6), a gradient by this
// fraction of its length; a point's terms are computed and summed in single precision
// in blocks of up to 64 points, which errs by at most 64 roundings of their magnitude.
constexpr double kDistanceError = 1e-5, kGradientError = 1e-5, kSumError = 64 * 0x1p-24;

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// One point's terms (scheduler/haptics/rigid_contact.h's formula) at distance phi with
// derivatives j = (dphi/dt, dphi/dtheta per radian in scene units).
struct Term {
  bool on = false;
  double energy = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero(), torque = Eigen::Vector3d::Zero();
  Matrix6d stiffness = Matrix6d::Zero();
};

Term term(const RigidContactModel& m, double phi, const Eigen::Vector3d& j_t, const Eigen::Vector3d& j_r, double area) {
  Term t;
  if (!(phi < -m.skin)) return t;
  const double u = m.metres_per_unit, k_a = m.pressure_stiffness * u * u * area, phi_m = u * (phi + m.skin);
  const Vector6d j = (Vector6d() << j_t, u * j_r).finished();
  t.on = true;
  t.energy = 0.5 * k_a * phi_m * phi_m;
  t.force = -k_a * phi_m * j_t;
  t.torque = -k_a * phi_m * u * j_r;
  t.stiffness = k_a * j * j.transpose();
  return t;
}

// The reference sums and how far an evaluation whose distances and gradients err by as
// much may lie from them: each point's first-order change; the whole term of a point
// within that error of the skin (it may count on one side and not the other); and for a
// point within that error of a fine cell's face (parts placed on the grid's planes), the
// change to the neighbouring cell's gradient (the trilinear gradient jumps there).
struct Reference {
  ContactWrench c;
  double energy_tol = 0, force_tol = 0, torque_tol = 0, stiffness_tol = 0;
  std::size_t uncertain = 0;  // points within the distance error of the skin
};

// Adds a point at p in `grid`'s frame; `derivatives` gives its j_t, j_r from the grid's gradient.
template <class Derivatives>
void add_point(Reference& ref, const RigidContactModel& m, const SignedDistanceGrid& grid, const Eigen::Vector3d& p,
               double area, const Derivatives& derivatives) {
  const double u = m.metres_per_unit, k_a = m.pressure_stiffness * u * u * area;
  const double h = grid.fine_spacing(), delta = kDistanceError * h;
  const auto at = [&](const Eigen::Vector3d& q, double& phi) {
    Eigen::Vector3d g, j_t, j_r;
    phi = sample_signed_distance(grid, q, &g);
    derivatives(g, j_t, j_r);
    return std::make_tuple(term(m, phi, j_t, j_r, area), j_t, j_r);
  };
  double phi = 0;
  const auto [t, j_t, j_r] = at(p, phi);
  const Vector6d j = (Vector6d() << j_t, u * j_r).finished();
  if (std::abs(phi + m.skin) <= delta) {
    ++ref.uncertain;
    ref.energy_tol += 0.5 * k_a * (u * delta) * (u * delta);
    ref.force_tol += k_a * u * delta * j_t.norm();
    ref.torque_tol += k_a * u * delta * u * j_r.norm();
    ref.stiffness_tol += k_a * j.squaredNorm();
  }
  // The cells on either side of the faces p lies on (within the error).
  const Eigen::Vector3d local = (p - grid.origin) / h;
  Eigen::Vector3d nudge = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    if (std::abs(local[a] - std::round(local[a])) <= kDistanceError) nudge[a] = 2 * delta;
  double force_jump = 0, torque_jump = 0, stiffness_jump = 0;
  if (nudge != Eigen::Vector3d::Zero())
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d side(corner & 1 ? 1 : -1, corner & 2 ? 1 : -1, corner & 4 ? 1 : -1);
      double other_phi = 0;
      const Term other = std::get<0>(at(p + nudge.cwiseProduct(side), other_phi));
      if (other.on != t.on) continue;  // across the skin: counted above
      force_jump = std::max(force_jump, (other.force - t.force).norm());
      torque_jump = std::max(torque_jump, (other.torque - t.torque).norm());
      stiffness_jump = std::max(stiffness_jump, (other.stiffness - t.stiffness).norm());
    }
  ref.force_tol += force_jump, ref.torque_tol += torque_jump, ref.stiffness_tol += stiffness_jump;
  if (!t.on) return;
  ContactWrench& c = ref.c;
  c.energy_j += t.energy;
  c.wrench.force += t.force;
  c.wrench.torque += t.torque;
  c.stiffness += t.stiffness;
  ++c.points;
  c.depth = std::max(c.depth, -phi);
  const double phi_m = u * (phi + m.skin);
  ref.energy_tol += k_a * std::abs(phi_m) * u * delta + kSumError * t.energy;
  ref.force_tol += k_a * (u * delta + (kGradientError + kSumError) * std::abs(phi_m)) * j_t.norm();
  ref.torque_tol += k_a * (u * delta + (kGradientError + kSumError) * std::abs(phi_m)) * u * j_r.norm();
  ref.stiffness_tol += (2 * kGradientError + kSumError) * k_a * j.squaredNorm();
}

// Every point, in double, as scheduler/haptics/rigid_contact.h defines the sum.
Reference reference_contact(const RigidContactModel& m, const Pose& pose) {
  Reference ref;
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  const Eigen::Vector3d& t = pose.translation;
  for (std::size_t i = 0; i < m.part2_samples.points.size(); ++i) {
    const Eigen::Vector3d arm = r * m.part2_samples.points[i];
    add_point(ref, m, m.part1_distance, arm + t, m.part2_samples.areas[i],
              [&](const Eigen::Vector3d& g, Eigen::Vector3d& j_t, Eigen::Vector3d& j_r) {
                j_t = g;
                j_r = arm.cross(g);
              });
  }
  for (std::size_t i = 0; i < m.part1_samples.points.size(); ++i) {
    const Eigen::Vector3d arm = m.part1_samples.points[i] - t;
    add_point(ref, m, m.part2_distance, r.transpose() * arm, m.part1_samples.areas[i],
              [&](const Eigen::Vector3d& g2, Eigen::Vector3d& j_t, Eigen::Vector3d& j_r) {
                const Eigen::Vector3d g = r * g2;
                j_t = -g;
                j_r = -arm.cross(g);
              });
  }
  return ref;
}

Pose about(const Pose& fit, const Eigen::Vector3d& shift, const Eigen::Vector3d& axis = Eigen::Vector3d::UnitX(),
           double deg = 0) {
  Pose p = fit;
  p.translation += shift;
  p.rotation = (Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized())) * fit.rotation).normalized();
  return p;
}

}  // namespace

TEST_CASE("rigid contact: the block evaluation agrees with the all-double sum about the shipped fits") {
  for (const char* file : {"default.json", "three_pegs.json", "peg_hole_clearance_0p5.json"}) {
    const Scene scene = test::shipped_scene(file);
    const AssemblyPair pair = prepare_assembly_pair(scene);
    const auto model = rigid_contact_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing);
    REQUIRE(model);
    const RigidContactModel& m = *model;
    const double h = m.part1_distance.fine_spacing();
    const Pose fit = *scene.assembled_pose;
    const Eigen::Vector3d x = Eigen::Vector3d::UnitX(), y = Eigen::Vector3d::UnitY(), z = Eigen::Vector3d::UnitZ();
    // Shifts other than whole spacings, but for one: the shipped parts lie on the grids'
    // planes, and so do their points at the fit and one spacing from it.
    const std::vector<Pose> poses = {
        fit,                                                        // aligned
        about(fit, h * x),                                          // into a wall, on the grid's planes
        about(fit, h * (0.007 * x - 0.83 * y + 0.011 * z)),         // into a wall
        about(fit, h * (0.013 * x + 0.009 * y - 0.47 * z)),         // onto a floor
        about(fit, h * (0.006 * x - 0.008 * y - 1.13 * z)),         // into the floor
        about(fit, h * (0.29 * x + 0.31 * y - 0.017 * z)),          // diagonally
        about(fit, Eigen::Vector3d::Zero(), x, 0.3),                // tilted
        about(fit, Eigen::Vector3d::Zero(), x + 2 * y, -0.6),       // tilted about an oblique axis
        about(fit, h * (0.41 * x + 0.007 * y - 0.33 * z), y, 0.4),  // shifted and tilted
        about(fit, -1.53 * x + 0.02 * y - 2.07 * z, x + y, 1.0),    // pushed 1.5-2 mm in: beyond the fine band
    };
    const auto threaded = contact_evaluator(model, 2);
    std::size_t touching = 0;
    for (std::size_t p = 0; p < poses.size(); ++p) {
      const Reference ref = reference_contact(m, poses[p]);
      CAPTURE(file);
      CAPTURE(p);
      for (const ContactWrench& c : {contact_wrench(m, poses[p]), threaded(poses[p])}) {
        MESSAGE(std::string(file) << " pose " << p << ": " << c.points << " points (reference " << ref.c.points << ", "
                                  << ref.uncertain << " at the skin), energy " << c.energy_j << " J (off by "
                                  << c.energy_j - ref.c.energy_j << ", allowed " << ref.energy_tol << "), force "
                                  << c.wrench.force.transpose() << " N (off by "
                                  << (c.wrench.force - ref.c.wrench.force).norm() << ", allowed " << ref.force_tol
                                  << "), stiffness off by " << (c.stiffness - ref.c.stiffness).norm() << " (allowed "
                                  << ref.stiffness_tol << ")");
        CHECK(c.points + ref.uncertain >= ref.c.points);
        CHECK(c.points <= ref.c.points + ref.uncertain);
        CHECK(std::abs(c.depth - ref.c.depth) <= kDistanceError * h);
        CHECK(std::abs(c.energy_j - ref.c.energy_j) <= ref.energy_tol);
        CHECK((c.wrench.force - ref.c.wrench.force).norm() <= ref.force_tol);
        CHECK((c.wrench.torque - ref.c.wrench.torque).norm() <= ref.torque_tol);
        CHECK((c.stiffness - ref.c.stiffness).norm() <= ref.stiffness_tol);
      }
      touching += ref.c.points;
    }
    CHECK(touching >= 500);  // the poses press the parts together
  }
}

TEST_CASE("rigid contact: a model whose point blocks do not match its samples is refused") {
  const Scene scene = test::shipped_scene("default.json");
  const AssemblyPair pair = prepare_assembly_pair(scene);
  RigidContactModel m = *rigid_contact_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing);
  m.part2_samples.points.push_back(Eigen::Vector3d::Zero());
  m.part2_samples.areas.push_back(1);
  CHECK_THROWS_AS(contact_wrench(m, *scene.assembled_pose), Error);
  prepare_rigid_contact(m);
  CHECK_NOTHROW(contact_wrench(m, *scene.assembled_pose));
}
