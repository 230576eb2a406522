#include "engine/query/error_estimate.h"

#include <cmath>

namespace snapfit {

ErrorEstimate estimate_error(const QueryResult& band_a, const QueryResult& band_b) {
  ErrorEstimate e;
  e.energy = kErrorEstimateScale * std::hypot(band_a.energy, band_b.energy);
  e.force = kErrorEstimateScale * std::sqrt(band_a.force.squaredNorm() + band_b.force.squaredNorm());
  e.torque = kErrorEstimateScale * std::sqrt(band_a.torque.squaredNorm() + band_b.torque.squaredNorm());
  return e;
}

}  // namespace snapfit
