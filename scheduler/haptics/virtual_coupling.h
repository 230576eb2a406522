#pragma once
// The 6-DOF virtual coupling between the haptic device and part 2 (seed 002 eq. 1-2):
// a spring-damper pulls the simulated part towards the device pose,
//     F = k_T d - b_T v,   tau = k_R theta - b_R omega
// with d, theta the translation and rotation from the part to the device and v, omega
// the part's velocity relative to the device; critically damped by default,
// b = 2 sqrt(k m) (iMSTK). The device is sent the reaction, -F and -tau.
//
// Units: poses in scene units (part 1's frame), forces in N, torques in N m, masses
// in kg; `metres_per_unit` converts. The part is a proxy with isotropic inertia about
// its frame origin (part 2's reference point, where the engine's torque acts), so
// translation and rotation decouple and no gyroscopic term arises.
//
// Integration (step_body): fixed step, implicit (backward Euler) in the coupling and
// explicit in the external (geometric) wrench. Backward Euler makes the coupling
// dissipative for any stiffness and step (the spring-damper energy can only fall), and
// a critically damped coupling stays free of overshoot in the discrete system too.
#include <Eigen/Core>

#include "snapfit/haptic_device.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/pose.h"

namespace snapfit {

// b = 2 zeta sqrt(k m): zeta = 1 is critical damping.
double critical_damping(double stiffness, double mass, double damping_ratio = 1.0);

// Coupling parameters with damping set from the damping ratio for both translation
// and rotation. Throws snapfit::Error for non-positive or non-finite inputs.
CouplingParams make_coupling(double metres_per_unit, double mass_kg, double inertia_kg_m2, double stiffness,
                             double rot_stiffness, double damping_ratio);

// The rotation vector theta with exp(theta) * from = to (shortest way, |theta| <= pi).
Eigen::Vector3d rotation_between(const Eigen::Quaterniond& from, const Eigen::Quaterniond& to);

// exp(theta) as a quaternion (theta a rotation vector).
Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& theta);

// The coupling wrench on the part (seed 002 eq. 1-2) for the device state `device`.
Wrench coupling_wrench(const BodyState& part, const BodyState& device, const CouplingParams& c);

// The coupling's stored energy plus the part's kinetic energy relative to a device
// at rest (J): 1/2 m v^2 + 1/2 I w^2 + 1/2 k d^2 + 1/2 k_R theta^2. For passivity checks.
double coupling_energy(const BodyState& part, const BodyState& device, const CouplingParams& c);

// Implicit extras of one step, on top of the coupling (snapfit/haptic_loop.h's
// passivity measures use them): damping of the part's own velocity (relative to part 1,
// not to the device), and the stiffness of the external wrench, linearised over the
// step, F(x') ~ F(x) - K (x' - x), so a stiff external force is integrated implicitly
// too. Both enter the backward-Euler denominators only: any non-negative values are
// stable, and they can only remove energy.
struct ImplicitExtras {
  double damping = 0;        // N s / m
  double rot_damping = 0;    // N m s / rad
  double stiffness = 0;      // N / m
  double rot_stiffness = 0;  // N m / rad
  // The full stiffness of a contact wrench (snapfit/haptic_loop.h ContactWrench), on
  // translation (m) and rotation (rad) together; symmetric positive semi-definite.
  Eigen::Matrix<double, 6, 6> contact_stiffness = Eigen::Matrix<double, 6, 6>::Zero();
};

// Advances the part by dt seconds under the coupling to `device` (implicit) and the
// external wrench (held over the step; explicit unless `extra` gives its stiffness).
void step_body(BodyState& part, const BodyState& device, const Wrench& external, const CouplingParams& c, double dt,
               const ImplicitExtras& extra = {});

}  // namespace snapfit
