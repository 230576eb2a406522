#pragma once
// Order statistics of timing samples (p50, p99 of frame and query times).
#include <vector>

namespace snapfit {

// p-quantile (0..1) of a sample by nearest rank; 0 for an empty one.
double quantile(std::vector<double> values, double p);

}  // namespace snapfit
