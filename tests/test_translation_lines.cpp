// The translation-only query's line selection (engine/query/translation_lines.h): for every
// m', the selected x-line intervals and extra terms must weigh each of the first m'
// modes of the mode order exactly once, in the real outputs and in Im f, and every
// other mode not at all. Checked node by node against the mode order, on small grids
// with even and odd axes (Nyquist planes or none), folded and unfolded.
#include <cstring>
#include <doctest/doctest.h>
#include <numeric>
#include <string>
#include <vector>

#include "engine/spectra/mode_order.h"
#include "engine/query/translation_lines.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

PairSpectra synthetic_spectra(std::array<std::size_t, 3> dims, Eigen::Vector3d length, int parity) {
  PairSpectra s;
  s.dims = dims;
  s.length = length;
  s.spacing = length.x() / double(dims[0]);
  const std::size_t total = dims[0] * dims[1] * dims[2];
  s.part1.rho.assign(total, Complex(0, 1));
  s.part2.rho.assign(total, Complex(0, 1));
  s.part1.sample_parity = s.part2.sample_parity = parity;
  return s;
}

std::array<int, 2> unpack_shorts(std::int32_t v) {
  std::int16_t pair[2];
  std::memcpy(pair, &v, sizeof v);
  return {pair[0], pair[1]};
}

std::size_t fft_node(const std::array<std::size_t, 3>& d, int kx, int ky, int kz) {
  auto wrap = [](int k, std::size_t n) { return k >= 0 ? std::size_t(k) : std::size_t(k + int(n)); };
  return wrap(kx, d[0]) + d[0] * (wrap(ky, d[1]) + d[1] * wrap(kz, d[2]));
}

// Weight of every FFT node in (real outputs, Im f) that the selection gives. A folded
// line node stands for its pair: weight (1, 1) on the node and on its partner (the
// pair's imaginary parts cancel, as two whole modes' do), or (2, 0) on a node without a
// partner.
void coverage(const TranslationLines& t, const LineSelection& sel, std::vector<int>& re, std::vector<int>& im) {
  const auto& d = t.dims;
  re.assign(d[0] * d[1] * d[2], 0);
  im.assign(re.size(), 0);
  for (const LineRecord& line : sel.lines) {
    const auto yz = unpack_shorts(line.kykz);
    REQUIRE(line.xa >= t.box_min[0]);
    REQUIRE(line.xb <= t.box_max[0]);
    REQUIRE(line.xa <= line.xb);
    // row0 is the box index of (0, ky, kz).
    CHECK(std::size_t(line.row0) ==
          std::size_t(-t.box_min[0]) +
              std::size_t(t.box_dims[0]) *
                  (std::size_t(yz[0] - t.box_min[1]) + std::size_t(t.box_dims[1]) * std::size_t(yz[1] - t.box_min[2])));
    for (int kx = line.xa; kx <= line.xb; ++kx) {
      const std::size_t k = fft_node(d, kx, yz[0], yz[1]);
      if (!sel.folded) {
        ++re[k];
        ++im[k];
        continue;
      }
      const std::size_t neg = negated_node(d, k);
      if (neg == kNoNode || neg == k) {
        re[k] += 2;
      } else {
        ++re[k], ++im[k], ++re[neg], ++im[neg];
      }
    }
  }
  for (const ExtraMode& e : sel.extras) {
    const auto xy = unpack_shorts(e.kxy), zc = unpack_shorts(e.kzc);
    const std::size_t k = fft_node(d, xy[0], xy[1], zc[0]);
    REQUIRE((zc[1] == 1 || zc[1] == 2));
    re[k] += zc[1] == 1 ? 1 : -1;
    im[k] += 1;
  }
}

}  // namespace

TEST_CASE("translation lines: every m' weighs exactly the first m' modes once, folded and unfolded") {
  struct Grid {
    std::array<std::size_t, 3> dims;
    Eigen::Vector3d length;
  };
  const std::vector<Grid> grids = {{{8, 8, 8}, {1, 1, 1}},
                                   {{12, 10, 9}, {1.2, 1.0, 0.9}},
                                   {{7, 9, 11}, {0.7, 0.9, 1.1}},
                                   {{16, 6, 10}, {1.6, 0.6, 1.0}}};
  for (const Grid& g : grids)
    for (const int parity : {-1, 0}) {
      const PairSpectra s = synthetic_spectra(g.dims, g.length, parity);
      const std::vector<std::size_t> order = mode_order(s);
      const TranslationLines t = build_translation_lines(s, order, true);
      const std::size_t total = order.size();
      CAPTURE(g.dims[0]);
      CAPTURE(g.dims[1]);
      CAPTURE(g.dims[2]);
      CAPTURE(parity);
      if (parity == 0) CHECK(t.fold_limit == 0);  // a complex correlation never folds
      if (parity != 0) {
        CHECK(t.fold_limit > total / 4);  // folding covers the low-pass ball well inside the grid
        const bool odd = g.dims[0] % 2 && g.dims[1] % 2 && g.dims[2] % 2;
        if (odd) CHECK(t.fold_limit == total);  // no Nyquist nodes: every m' folds
      }
      LineSelection sel;
      std::vector<int> re, im;
      std::size_t folded_count = 0;
      for (std::size_t m = 1; m <= total; ++m) {
        CAPTURE(m);
        select_lines(t, m, sel);
        CHECK(sel.folded == (parity != 0 && m <= t.fold_limit));
        folded_count += sel.folded ? 1 : 0;
        coverage(t, sel, re, im);
        std::size_t wrong = 0, nodes = 0;
        for (std::size_t i = 0; i < total; ++i) {
          const int want = i < m ? 1 : 0;
          if (re[order[i]] != want || im[order[i]] != want) ++wrong;
        }
        for (const LineRecord& line : sel.lines) nodes += std::size_t(line.xb - line.xa + 1);
        CHECK(wrong == 0);
        CHECK(sel.nodes == nodes);
        // Folding halves the terms: one node per pair (plus nodes without partners).
        if (sel.folded)
          CHECK(sel.nodes <= (m + 1) / 2 + kMaxUnpairedExtras + 1);
        else
          CHECK(sel.nodes == m);
      }
      if (parity != 0) CHECK(folded_count == t.fold_limit);
    }
}

TEST_CASE("translation lines: a mode order that is not monotone along an x-line is refused with the line named") {
  const PairSpectra s = synthetic_spectra({8, 8, 8}, {1, 1, 1}, -1);
  std::vector<std::size_t> order = mode_order(s);
  // Swap the nodes (1, 0, 0) and (2, 0, 0) of the centre line.
  const auto a = std::find(order.begin(), order.end(), std::size_t(1));
  const auto b = std::find(order.begin(), order.end(), std::size_t(2));
  std::iter_swap(a, b);
  CHECK_THROWS_WITH_AS(build_translation_lines(s, order, false), doctest::Contains("(ky 0, kz 0) at kx 2"), Error);
  std::vector<std::size_t> short_order(order.begin(), order.end() - 1);
  CHECK_THROWS_WITH_AS(build_translation_lines(s, short_order, false), doctest::Contains("every FFT node"), Error);
}

}  // namespace snapfit
