#pragma once
// The order in which queries retain modes (the "dominant" ones: the low-pass ball
// |w| <= K grows with m'), shared by the device engine (include/snapfit/query.h) and the
// host reference (engine/query/reference_query.h) so that both sum the same m' modes.
#include <cstddef>
#include <limits>
#include <vector>

#include "engine/spectra/spectra.h"

namespace snapfit {

constexpr std::size_t kNoNode = std::numeric_limits<std::size_t>::max();

// The FFT node (index x + nx (y + ny z)) of frequency -w for node k, or kNoNode when
// -w is not a node: a component at the Nyquist index n/2 of an even axis (its negation,
// -n/2, wraps to the same index, which stands for +n/2). Node 0 is its own negation.
std::size_t negated_node(const std::array<std::size_t, 3>& dims, std::size_t k);

// The signed frequency indices (kx, ky, kz) of FFT node k (signed_index per axis).
std::array<int, 3> signed_node(const std::array<std::size_t, 3>& dims, std::size_t k);

// Every FFT node by increasing |w| (in float), ties ordered so that w and -w are
// adjacent (by the pair's smaller node index, then the node index): a prefix of any
// length splits at most one conjugate pair.
std::vector<std::size_t> mode_order(const PairSpectra& spectra);

// reach[i]: the largest |k| on any axis among the modes order[0 .. i] (how far the
// per-axis phase tables of a query at m' = i + 1 must go).
std::vector<int> mode_reach(const std::array<std::size_t, 3>& dims, const std::vector<std::size_t>& order);

}  // namespace snapfit
