#include "core/quantile.h"

#include <algorithm>
#include <cmath>

namespace snapfit {

double quantile(std::vector<double> values, double p) {
  if (values.empty()) return 0;
  // Nearest rank: the smallest value with at least a fraction p of the sample at or below it.
  const double r = std::ceil(std::clamp(p, 0.0, 1.0) * values.size());
  const std::size_t rank = r < 1 ? 0 : std::min(values.size() - 1, static_cast<std::size_t>(r) - 1);
  std::nth_element(values.begin(), values.begin() + rank, values.end());
  return values[rank];
}

}  // namespace snapfit
