#pragma once
// The cell of a regular grid of `spacing` that holds a point, as one 64-bit key (21 bits
// per axis, wrapping beyond +-2^20 cells) and the cell's centre: for thinning point sets
// to about one point per cell.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>

namespace snapfit {

inline std::uint64_t cell_key(const Eigen::Vector3d& p, double spacing, Eigen::Vector3d& centre) {
  std::uint64_t key = 0;
  for (int k = 0; k < 3; ++k) {
    const double cell = std::floor(p[k] / spacing);
    centre[k] = (cell + 0.5) * spacing;
    key = key * 2097152 + static_cast<std::uint64_t>(static_cast<std::int64_t>(cell) + 1048576) % 2097152;
  }
  return key;
}

}  // namespace snapfit
