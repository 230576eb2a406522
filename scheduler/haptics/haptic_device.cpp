#include "snapfit/haptic_device.h"

namespace snapfit {

Wrench clamp_to_limits(const Wrench& wrench, const DeviceLimits& limits) {
  Wrench out;
  if (!wrench.force.allFinite() || !wrench.torque.allFinite()) return out;
  const auto clamp = [](const Eigen::Vector3d& v, double limit) -> Eigen::Vector3d {
    const double n = v.norm();
    if (!(limit > 0)) return Eigen::Vector3d::Zero();
    return n > limit ? Eigen::Vector3d(v * (limit / n)) : v;
  };
  out.force = clamp(wrench.force, limits.max_force_n);
  out.torque = clamp(wrench.torque, limits.max_torque_nm);
  return out;
}

}  // namespace snapfit
