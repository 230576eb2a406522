#pragma once
// A cube of sample points for the tests with analytic fields.
#include "core/grid.h"

namespace snapfit::test {

// n^3 points h apart about `centre`, shifted by 0.013 so no sample sits on the centre.
inline GridSpec cube_grid(const Eigen::Vector3d& centre, int n, double h) {
  GridSpec g;
  g.spacing = h;
  g.dims = Eigen::Vector3i(n, n, n);
  g.origin = centre - Eigen::Vector3d::Constant(h * (n - 1) / 2.0 + 0.013);
  return g;
}

}  // namespace snapfit::test
