#include "scheduler/haptics/rendered_wrench.h"

#include <Eigen/Cholesky>
#include <cmath>

#include "scheduler/haptics/virtual_coupling.h"

namespace snapfit {

RenderedWrench rendered_wrench(const WrenchEvaluator& engine, double gain,
                               const std::function<ContactWrench(const Pose&)>& contact, double u, const Pose& pose) {
  RenderedWrench r;
  const QueryResult q = engine.evaluate(pose);
  r.flags = q.flags;
  if (q.flags == query_ok) {
    r.wrench.force = gain * q.force;
    r.wrench.torque = gain * u * q.torque;
    r.potential_j = gain * u * q.energy;
  }
  if (contact) {
    r.contact = contact(pose);
    r.wrench.force += r.contact.wrench.force;
    r.wrench.torque += r.contact.wrench.torque;
    r.potential_j += r.contact.energy_j;
  }
  return r;
}

RestPoint descend_rendered(const WrenchEvaluator& engine, double gain,
                           const std::function<ContactWrench(const Pose&)>& contact, const CouplingParams& coupling,
                           const Pose& start, int max_steps) {
  const double u = coupling.metres_per_unit;
  RestPoint rest{start, 0, 0};
  RenderedWrench at = rendered_wrench(engine, gain, contact, u, start);
  rest.potential_j = at.potential_j;
  double damping = 1;  // grows when a step fails, shrinks when one succeeds
  for (; rest.steps < max_steps; ++rest.steps) {
    Eigen::Matrix<double, 6, 6> h = at.contact.stiffness;
    h.diagonal().head<3>().array() += damping * coupling.stiffness;
    h.diagonal().tail<3>().array() += damping * coupling.rot_stiffness;
    Eigen::Matrix<double, 6, 1> w;
    w << at.wrench.force, at.wrench.torque;
    const Eigen::Matrix<double, 6, 1> dx = h.ldlt().solve(w);  // metres, radians
    Pose next = rest.pose;
    next.translation += dx.head<3>() / u;
    next.rotation = (rotation_exp(dx.tail<3>()) * rest.pose.rotation).normalized();
    const RenderedWrench there = rendered_wrench(engine, gain, contact, u, next);
    if (there.flags == query_ok && there.potential_j < at.potential_j) {
      rest.pose = next;
      rest.potential_j = there.potential_j;
      at = there;
      damping = std::max(damping / 2, 1e-3);
      if (dx.head<3>().norm() / u < 1e-6 && dx.tail<3>().norm() < 1e-6) break;
    } else {
      damping *= 4;
      if (damping > 1e8) break;
    }
  }
  return rest;
}

RenderedStiffness rendered_stiffness(const WrenchEvaluator& engine, double geometry_gain,
                                     const std::function<ContactWrench(const Pose&)>& contact,
                                     const CouplingParams& coupling, const Pose& pose) {
  RenderedStiffness s;
  const double u = coupling.metres_per_unit;
  const double step = s.step_mm * 1e-3 / u;  // scene units
  const double tilt = s.tilt_deg * M_PI / 180;
  const Wrench at = rendered_wrench(engine, geometry_gain, contact, u, pose).wrench;
  for (int i = 0; i < 6; ++i) {
    const Eigen::Vector3d e = (i % 2 ? -1.0 : 1.0) * Eigen::Vector3d::Unit(i / 2);
    Pose moved = pose;
    moved.translation += step * e;
    s.force_n_per_mm[i] = -(rendered_wrench(engine, geometry_gain, contact, u, moved).wrench.force - at.force).dot(e) / s.step_mm;
    Pose turned = pose;
    turned.rotation = (rotation_exp(tilt * e) * pose.rotation).normalized();
    s.torque_nm_per_deg[i] =
        -(rendered_wrench(engine, geometry_gain, contact, u, turned).wrench.torque - at.torque).dot(e) / s.tilt_deg;
  }
  s.coupling_n_per_mm = coupling.stiffness * 1e-3;
  s.coupling_nm_per_deg = coupling.rot_stiffness * M_PI / 180;
  return s;
}

}  // namespace snapfit
