#include "engine/query/translation_lines.h"

#include <algorithm>
#include <cstring>
#include <limits>
#include <numeric>
#include <string>

#include "engine/spectra/mode_order.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

using Key = std::uint32_t;
constexpr Key kExcluded = std::numeric_limits<Key>::max();

std::size_t fft_index(int k, std::size_t n) { return k >= 0 ? std::size_t(k) : std::size_t(k + int(n)); }

std::int32_t pack_shorts(int a, int b) {
  const std::int16_t pair[2] = {static_cast<std::int16_t>(a), static_cast<std::int16_t>(b)};
  std::int32_t out;
  std::memcpy(&out, pair, sizeof out);  // the kernel's as_short2: .x = a, .y = b
  return out;
}

// Groups the nodes with a key (key_of(FFT node) != kExcluded) into x-lines ordered by
// their first key. On each side of kx = 0 the kept nodes must start at the centre and
// their keys grow with |kx| (true of any |w| order), so that a key threshold keeps one
// interval per line.
template <class KeyOf>
LineSet group_lines(const TranslationLines& t, KeyOf key_of) {
  const auto& d = t.dims;
  struct Line {
    Key first;
    int ky, kz;
    std::vector<Key> right, left;
  };
  std::vector<Line> lines;
  for (std::size_t z = 0; z < d[2]; ++z)
    for (std::size_t y = 0; y < d[1]; ++y) {
      Line line{kExcluded, signed_index(y, d[1]), signed_index(z, d[2]), {}, {}};
      for (int side = 0; side < 2; ++side) {
        std::vector<Key>& out = side == 0 ? line.right : line.left;
        const int step = side == 0 ? 1 : -1;
        bool ended = false;
        for (int kx = side == 0 ? 0 : -1; kx >= t.box_min[0] && kx <= t.box_max[0]; kx += step) {
          const Key key = key_of(fft_index(kx, d[0]) + d[0] * (y + d[1] * z), kx, line.ky, line.kz);
          if (key == kExcluded) {
            ended = true;
            continue;
          }
          if (ended || (!out.empty() && key <= out.back()))
            throw Error("translation-only lines: the mode order is not monotone along the x-line (ky " +
                        std::to_string(line.ky) + ", kz " + std::to_string(line.kz) + ") at kx " + std::to_string(kx));
          out.push_back(key);
        }
        if (!out.empty()) line.first = std::min(line.first, out.front());
      }
      if (line.first != kExcluded) lines.push_back(std::move(line));
    }
  std::sort(lines.begin(), lines.end(), [](const Line& a, const Line& b) { return a.first < b.first; });
  LineSet set;
  for (const Line& line : lines) {
    set.row0.push_back(static_cast<std::int32_t>(box_node(t, 0, line.ky, line.kz)));
    set.kykz.push_back(pack_shorts(line.ky, line.kz));
    set.first_key.push_back(line.first);
    set.right_begin.push_back(set.keys.size());
    set.keys.insert(set.keys.end(), line.right.begin(), line.right.end());
    set.left_begin.push_back(set.keys.size());
    set.keys.insert(set.keys.end(), line.left.begin(), line.left.end());
  }
  set.right_begin.push_back(set.keys.size());
  return set;
}

ExtraMode extra_mode(const TranslationLines& t, std::size_t node, int code) {
  const std::array<int, 3> k = signed_node(t.dims, node);
  const std::complex<float> w =
      t.weights.empty() ? std::complex<float>(0, 0) : t.weights[box_node(t, k[0], k[1], k[2])];
  return ExtraMode{w.real(), w.imag(), pack_shorts(k[0], k[1]), pack_shorts(k[2], code)};
}

}  // namespace

std::size_t box_node(const TranslationLines& t, int kx, int ky, int kz) {
  return std::size_t(kx - t.box_min[0]) +
         std::size_t(t.box_dims[0]) *
             (std::size_t(ky - t.box_min[1]) + std::size_t(t.box_dims[1]) * std::size_t(kz - t.box_min[2]));
}

TranslationLines build_translation_lines(const std::array<std::size_t, 3>& dims, const std::vector<std::size_t>& order,
                                         bool conjugate_pairs, std::size_t max_modes) {
  TranslationLines t;
  t.dims = dims;
  const auto& d = t.dims;
  const std::size_t total = d[0] * d[1] * d[2];
  if (order.size() != total) throw Error("translation-only lines: the mode order does not list every FFT node");
  if (total >= std::size_t(kExcluded))
    throw Error("translation-only lines: FFT grid of " + std::to_string(total) + " nodes is too large");
  t.max_modes = max_modes == 0 ? total : std::min(max_modes, total);
  // The box: every signed index of the first max_modes modes (8 nodes of padding along x:
  // the translation kernel reads 8-wide chunks).
  std::array<int, 3> reach{0, 0, 0};
  for (std::size_t i = 0; i < t.max_modes; ++i) {
    const std::array<int, 3> k = signed_node(d, order[i]);
    for (int a = 0; a < 3; ++a) reach[a] = std::max(reach[a], std::abs(k[a]));
  }
  for (int a = 0; a < 3; ++a) {
    t.box_max[a] = std::min(int(d[a] / 2), reach[a]);
    t.box_min[a] = std::max(int(d[a] / 2) - int(d[a]) + 1, -reach[a]);
    t.box_dims[a] = t.box_max[a] - t.box_min[a] + 1 + (a == 0 ? 8 : 0);
  }
  t.order.resize(total);
  std::vector<Key> rank(total);
  for (std::size_t i = 0; i < total; ++i) {
    t.order[i] = static_cast<std::uint32_t>(order[i]);
    rank[order[i]] = i < t.max_modes ? static_cast<Key>(i) : kExcluded;
  }
  t.unfolded = group_lines(t, [&](std::size_t k, int, int, int) { return rank[k]; });
  if (!conjugate_pairs) return t;

  // Folded: one member of each pair (the visited half), keyed by the later of the two
  // ranks; unpartnered nodes keyed by their own rank.
  auto visited = [](int kx, int ky, int kz) { return kz > 0 || (kz == 0 && (ky > 0 || (ky == 0 && kx >= 0))); };
  t.fold_limit = t.max_modes;
  for (std::size_t i = 0; i < t.max_modes; ++i) {
    const std::size_t k = order[i], neg = negated_node(d, k);
    if (neg != kNoNode && neg != k) continue;
    const std::array<int, 3> kk = signed_node(d, k);
    const bool seen = visited(kk[0], kk[1], kk[2]);
    if (!seen || t.unpaired_visited_ranks.size() == kMaxUnpairedExtras) {
      t.fold_limit = i;  // the folded lines would miss this node (or need one correction too many)
      break;
    }
    t.unpaired_visited_ranks.push_back(static_cast<std::uint32_t>(i));
  }
  if (t.fold_limit == 0) return t;
  t.folded = group_lines(t, [&](std::size_t k, int kx, int ky, int kz) {
    if (!visited(kx, ky, kz)) return kExcluded;
    const std::size_t neg = negated_node(d, k);
    return neg == kNoNode || neg == k ? rank[k] : std::max(rank[k], rank[neg]);
  });
  return t;
}

void fill_translation_weights(TranslationLines& t, const PairSpectra& spectra) {
  const auto& d = t.dims;
  t.weights.assign(std::size_t(t.box_dims[0]) * t.box_dims[1] * t.box_dims[2], std::complex<float>(0, 0));
  // W_k = S1(w_k) S2(-w_k) dw (docs/design.md; seed 000 section 3.3), S2(-w_k) at node -k
  // (a Nyquist index wraps onto itself).
  const double dw = 1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z());
  for (std::size_t i = 0; i < t.max_modes; ++i) {
    const std::size_t k = t.order[i];
    const std::size_t x = k % d[0], y = (k / d[0]) % d[1], z = k / (d[0] * d[1]);
    const std::size_t neg = (d[0] - x) % d[0] + d[0] * ((d[1] - y) % d[1] + d[1] * ((d[2] - z) % d[2]));
    const std::array<int, 3> kk = signed_node(d, k);
    t.weights[box_node(t, kk[0], kk[1], kk[2])] =
        spectra.part1.rho[k] * static_cast<float>(dw) * spectra.part2.rho[neg];
  }
}

TranslationLines build_translation_lines(const PairSpectra& spectra, const std::vector<std::size_t>& order, bool fold) {
  TranslationLines t = build_translation_lines(spectra.dims, order, fold && spectra.conjugate_pairs() == 1);
  fill_translation_weights(t, spectra);
  return t;
}

void select_lines(const TranslationLines& t, std::size_t modes, LineSelection& out) {
  out.modes = modes;
  out.folded = !t.folded.first_key.empty() && modes <= t.fold_limit;
  const LineSet& set = out.folded ? t.folded : t.unfolded;
  const Key m = static_cast<Key>(modes);
  const std::size_t n =
      static_cast<std::size_t>(std::lower_bound(set.first_key.begin(), set.first_key.end(), m) - set.first_key.begin());
  out.lines.resize(n);
  out.nodes = 0;
  const Key* keys = set.keys.data();
  // Line j's retained kx below key `limit`: [-left, right - 1], empty as [0, -1].
  const auto interval = [&](std::size_t j, Key limit, std::int32_t& a, std::int32_t& b) {
    const std::size_t right = static_cast<std::size_t>(
        std::lower_bound(keys + set.right_begin[j], keys + set.left_begin[j], limit) - (keys + set.right_begin[j]));
    const std::size_t left = static_cast<std::size_t>(
        std::lower_bound(keys + set.left_begin[j], keys + set.right_begin[j + 1], limit) - (keys + set.left_begin[j]));
    a = right + left == 0 ? 0 : -static_cast<std::int32_t>(left);
    b = right + left == 0 ? -1 : static_cast<std::int32_t>(right) - 1;
    return left + right;
  };
  for (std::size_t j = 0; j < n; ++j) {
    LineRecord& r = out.lines[j];
    r.row0 = set.row0[j];
    r.kykz = set.kykz[j];
    out.nodes += interval(j, m, r.xa, r.xb);
    interval(j, m / 2, r.ha, r.hb);
    interval(j, m / 4, r.qa, r.qb);
  }
  out.extras.clear();
  if (!out.folded) return;
  // The pair that m' cuts: its first mode (rank m' - 1) alone.
  if (modes < t.order.size()) {  // (the box holds the first max_modes modes; m' <= max_modes)
    const std::size_t k = t.order[modes - 1], neg = negated_node(t.dims, k);
    if (neg != kNoNode && neg != k && t.order[modes] == neg) out.extras.push_back(extra_mode(t, k, 1));
  }
  for (const std::uint32_t r : t.unpaired_visited_ranks) {
    if (r >= modes) break;
    out.extras.push_back(extra_mode(t, t.order[r], 2));
  }
}

}  // namespace snapfit
