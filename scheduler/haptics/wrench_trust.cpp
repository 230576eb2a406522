#include "scheduler/haptics/wrench_trust.h"

#include <algorithm>
#include <cmath>

namespace snapfit {

double quantity_trust(double value, double error, double relative, double floor) {
  value = std::abs(value);
  if (!std::isfinite(value) || !std::isfinite(error)) return 0;
  const double allowed = std::max(relative * value, floor);
  if (error <= allowed) return 1;
  const double ramp = std::max(0.0, 1.0 - relative) * value;
  if (!(ramp > 0)) return 0;
  return std::clamp(1.0 - (error - allowed) / ramp, 0.0, 1.0);
}

double wrench_trust(const Wrench& wrench, const ErrorEstimate& error, const WrenchTrust& trust) {
  if (!trust.enabled) return 1;
  return std::min(quantity_trust(wrench.force.norm(), error.force, trust.relative, trust.force_n),
                  quantity_trust(wrench.torque.norm(), error.torque, trust.relative, trust.torque_nm));
}

}  // namespace snapfit
