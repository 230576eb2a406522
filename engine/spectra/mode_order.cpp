#include "engine/spectra/mode_order.h"

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <tuple>

namespace snapfit {

std::size_t negated_node(const std::array<std::size_t, 3>& dims, std::size_t k) {
  const std::size_t x = k % dims[0], y = (k / dims[0]) % dims[1], z = k / (dims[0] * dims[1]);
  const std::size_t index[3] = {x, y, z};
  std::size_t neg[3];
  for (int a = 0; a < 3; ++a) {
    if (dims[a] % 2 == 0 && index[a] == dims[a] / 2) return kNoNode;
    neg[a] = (dims[a] - index[a]) % dims[a];
  }
  return neg[0] + dims[0] * (neg[1] + dims[1] * neg[2]);
}

std::array<int, 3> signed_node(const std::array<std::size_t, 3>& dims, std::size_t k) {
  return {signed_index(k % dims[0], dims[0]), signed_index((k / dims[0]) % dims[1], dims[1]),
          signed_index(k / (dims[0] * dims[1]), dims[2])};
}

std::vector<std::size_t> mode_order(const PairSpectra& s) {
  const auto& d = s.dims;
  const std::size_t total = d[0] * d[1] * d[2];
  std::vector<float> norm2(total);
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y)
      for (std::size_t x = 0; x < d[0]; ++x) {
        const float wx = float(s.frequency(0, x)), wy = float(s.frequency(1, y)), wz = float(s.frequency(2, z));
        norm2[x + d[0] * (y + d[1] * z)] = wx * wx + wy * wy + wz * wz;
      }
  // w and -w have the same float |w|^2 (negation is exact), so the pair key (the pair's
  // smaller node) keeps them together within their tie.
  std::vector<std::size_t> pair_key(total);
  for (std::size_t k = 0; k < total; ++k) pair_key[k] = std::min(k, negated_node(d, k));
  std::vector<std::size_t> order(total);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return std::make_tuple(norm2[a], pair_key[a], a) < std::make_tuple(norm2[b], pair_key[b], b);
  });
  return order;
}

std::vector<int> mode_reach(const std::array<std::size_t, 3>& dims, const std::vector<std::size_t>& order) {
  std::vector<int> reach(order.size());
  int largest = 0;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::array<int, 3> k = signed_node(dims, order[i]);
    largest = std::max({largest, std::abs(k[0]), std::abs(k[1]), std::abs(k[2])});
    reach[i] = largest;
  }
  return reach;
}

}  // namespace snapfit
