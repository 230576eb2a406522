#include "engine/query/collision_predicate.h"

#include <algorithm>
#include <cmath>

#include "engine/spectra/mode_order.h"

namespace snapfit {

double TruncationTails::bound(std::size_t modes) const {
  const std::size_t m = std::min(modes, tail1.size() - 1);
  return dw * std::sqrt(std::max(0.0, tail1[m]) * std::max(0.0, tail2[m]));
}

TruncationTails truncation_tails(const PairSpectra& spectra) {
  const std::vector<std::size_t> order = mode_order(spectra);
  TruncationTails t;
  t.dw = 1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z());
  t.tail1.assign(order.size() + 1, 0.0);
  t.tail2.assign(order.size() + 1, 0.0);
  // Suffix sums from the highest |w| down, so the small terms are added first.
  for (std::size_t i = order.size(); i-- > 0;) {
    t.tail1[i] = t.tail1[i + 1] + std::norm(std::complex<double>(spectra.part1.rho[order[i]]));
    t.tail2[i] = t.tail2[i + 1] + std::norm(std::complex<double>(spectra.part2.rho[order[i]]));
  }
  return t;
}

CollisionVerdict collision_verdict(const QueryResult& result, const TruncationTails& tails) {
  CollisionVerdict v;
  v.overlap = result.energy;
  v.bound = tails.bound(result.modes);
  v.collides = result.flags == query_ok && v.overlap > v.bound;
  return v;
}

}  // namespace snapfit
