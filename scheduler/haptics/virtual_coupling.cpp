#include "scheduler/haptics/virtual_coupling.h"

#include <Eigen/Cholesky>
#include <cmath>
#include <string>

#include "snapfit/error.h"

namespace snapfit {

double critical_damping(double stiffness, double mass, double damping_ratio) {
  return 2.0 * damping_ratio * std::sqrt(stiffness * mass);
}

CouplingParams make_coupling(double metres_per_unit, double mass_kg, double inertia_kg_m2, double stiffness,
                             double rot_stiffness, double damping_ratio) {
  const auto check = [](double v, const char* what) {
    if (!(std::isfinite(v) && v > 0))
      throw Error(std::string("virtual coupling: ") + what + " must be > 0 (got " + std::to_string(v) + ")");
  };
  check(metres_per_unit, "metres per unit");
  check(mass_kg, "mass");
  check(inertia_kg_m2, "inertia");
  check(stiffness, "stiffness");
  check(rot_stiffness, "rotational stiffness");
  if (!(std::isfinite(damping_ratio) && damping_ratio >= 0))
    throw Error("virtual coupling: damping ratio must be >= 0 (got " + std::to_string(damping_ratio) + ")");
  CouplingParams c;
  c.metres_per_unit = metres_per_unit;
  c.mass_kg = mass_kg;
  c.inertia_kg_m2 = inertia_kg_m2;
  c.stiffness = stiffness;
  c.rot_stiffness = rot_stiffness;
  c.damping = critical_damping(stiffness, mass_kg, damping_ratio);
  c.rot_damping = critical_damping(rot_stiffness, inertia_kg_m2, damping_ratio);
  return c;
}

Eigen::Vector3d rotation_between(const Eigen::Quaterniond& from, const Eigen::Quaterniond& to) {
  Eigen::Quaterniond d = to.normalized() * from.normalized().conjugate();
  if (d.w() < 0) d.coeffs() = -d.coeffs();  // the shorter of the two ways round
  const double s = d.vec().norm();
  if (s < 1e-12) return 2.0 * d.vec();  // small angle: theta ~ 2 sin(theta/2) axis
  return (2.0 * std::atan2(s, d.w()) / s) * d.vec();
}

Eigen::Quaterniond rotation_exp(const Eigen::Vector3d& theta) {
  const double angle = theta.norm();
  if (angle < 1e-12) return Eigen::Quaterniond(1.0, 0.5 * theta.x(), 0.5 * theta.y(), 0.5 * theta.z()).normalized();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, theta / angle));
}

Wrench coupling_wrench(const BodyState& part, const BodyState& device, const CouplingParams& c) {
  const double u = c.metres_per_unit;
  Wrench w;
  // seed 002 eq. 1: F = k_T d - b_T v (v relative to the device), in SI units.
  w.force = c.stiffness * u * (device.pose.translation - part.pose.translation) -
            c.damping * u * (part.velocity - device.velocity);
  // seed 002 eq. 2: tau = k_R theta - b_R omega.
  w.torque = c.rot_stiffness * rotation_between(part.pose.rotation, device.pose.rotation) -
             c.rot_damping * (part.angular_velocity - device.angular_velocity);
  return w;
}

double coupling_energy(const BodyState& part, const BodyState& device, const CouplingParams& c) {
  const double u = c.metres_per_unit;
  const double d2 = (u * (device.pose.translation - part.pose.translation)).squaredNorm();
  const double theta2 = rotation_between(part.pose.rotation, device.pose.rotation).squaredNorm();
  return 0.5 * c.mass_kg * (u * part.velocity).squaredNorm() +
         0.5 * c.inertia_kg_m2 * part.angular_velocity.squaredNorm() + 0.5 * c.stiffness * d2 +
         0.5 * c.rot_stiffness * theta2;
}

void step_body(BodyState& part, const BodyState& device, const Wrench& external, const CouplingParams& c, double dt,
               const ImplicitExtras& extra) {
  const double u = c.metres_per_unit;
  // Backward Euler with x' = x + dt v' in translation (beta, K: the extras' damping and
  // isotropic external stiffness, F(x') ~ F(x) - K dt v'):
  //   m (v' - v) = dt [k (x_d - x') - b (v' - v_d) - beta v' + F(x')]
  //   v' (m + dt (b + beta) + dt^2 (k + K)) = m v + dt [k (x_d - x) + b v_d + F(x)]      (SI units)
  // and the same in rotation with the rotation error linearised over the step,
  // theta' ~ theta - dt w':  w' (I + dt b_R + dt^2 k_R) = I w + dt [k_R theta + b_R w_d + tau].
  // A contact stiffness C couples the two: [diag(...) + dt^2 C] (v', w') = (right-hand sides).
  const Eigen::Vector3d v = u * part.velocity;
  const Eigen::Vector3d d = u * (device.pose.translation - part.pose.translation);
  const Eigen::Vector3d theta = rotation_between(part.pose.rotation, device.pose.rotation);
  const Eigen::Vector3d rhs_t = c.mass_kg * v + dt * (c.stiffness * d + c.damping * u * device.velocity + external.force);
  const Eigen::Vector3d rhs_r =
      c.inertia_kg_m2 * part.angular_velocity +
      dt * (c.rot_stiffness * theta + c.rot_damping * device.angular_velocity + external.torque);
  const double diag_t =
      c.mass_kg + dt * (c.damping + extra.damping) + dt * dt * (c.stiffness + extra.stiffness);
  const double diag_r = c.inertia_kg_m2 + dt * (c.rot_damping + extra.rot_damping) +
                        dt * dt * (c.rot_stiffness + extra.rot_stiffness);
  Eigen::Vector3d v_new, w_new;
  if (extra.contact_stiffness.isZero(0)) {
    v_new = rhs_t / diag_t;
    w_new = rhs_r / diag_r;
  } else {
    Eigen::Matrix<double, 6, 6> a = dt * dt * extra.contact_stiffness;
    a.diagonal().head<3>().array() += diag_t;
    a.diagonal().tail<3>().array() += diag_r;
    Eigen::Matrix<double, 6, 1> rhs;
    rhs << rhs_t, rhs_r;
    const Eigen::Matrix<double, 6, 1> x = a.ldlt().solve(rhs);
    v_new = x.head<3>();
    w_new = x.tail<3>();
  }
  part.velocity = v_new / u;
  part.pose.translation += dt * part.velocity;
  part.angular_velocity = w_new;
  part.pose.rotation = (rotation_exp(dt * part.angular_velocity) * part.pose.rotation).normalized();
}

}  // namespace snapfit
