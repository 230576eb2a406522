#pragma once
// The translation-only query's data (seed 000 section 3.3; kernels/pose_query.cl
// translation_lines): the product W_k = S1(w_k) S2(-w_k) dw in a dense box of x-lines,
// and, for each m', the lines and kx intervals that hold exactly the first m' modes of
// the mode order (engine/spectra/mode_order.h).
//
// Along an x-line (ky, kz fixed) |w| grows with |kx| on each side of kx = 0, so the
// retained nodes of a line always form one interval [xa, xb] around kx = 0: the kernel
// streams that interval with no per-node rank test, and visits no line outside the
// low-pass ball.
//
// Conjugate pairs (a real correlation, PairSpectra::conjugate_pairs): the terms at k and
// -k are complex conjugates, so the folded sum visits only the lines with kz > 0, or
// kz = 0 and ky >= 0 (kx >= 0 on the centre line), counts each node twice in the real
// outputs (Re f, F) and not at all in Im f. Its intervals hold the pairs with both modes
// among the first m'. Extra modes correct the rest, one term each:
//   - the pair that m' cuts: its first mode alone, weight (1, 1) in (real, Im f);
//   - a retained node without a partner (node 0, Nyquist components) that the folded
//     lines counted twice: weight (-1, +1).
// Folding runs while m' <= fold_limit: below the first unpartnered node of a line the
// folded sum skips, and below the (kMaxUnpairedExtras + 1)-th unpartnered node it visits.
#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "engine/spectra/spectra.h"

namespace snapfit {

// One line of the current selection, as the kernel reads it (int8): the index in the
// weight box of the line's node kx = 0, (ky, kz) as two 16-bit halves (ky low), the
// interval [xa, xb] of retained kx, and within it the intervals of the modes among the
// first m'/2 ([ha, hb]) and m'/4 ([qa, qb]), for the band sums of the error estimate.
// An empty interval is [0, -1] (every non-empty one holds kx = 0).
struct LineRecord {
  std::int32_t row0 = 0, kykz = 0, xa = 0, xb = -1, ha = 0, hb = -1, qa = 0, qb = -1;
};

// One extra mode (float4): W_k, (kx, ky) and (kz, weight code) as 16-bit halves; code 1:
// weight 1 in every output (a cut pair's mode), code 2: -1 in the real outputs and +1 in
// Im f (an unpartnered node counted twice by the folded lines).
struct ExtraMode {
  float re = 0, im = 0;
  std::int32_t kxy = 0, kzc = 0;
};

constexpr std::size_t kMaxUnpairedExtras = 16;

// Lines that can hold retained modes, ordered by their first node's key, and per line
// the keys of its nodes on each side of kx = 0 (increasing with |kx|): a node is kept at
// m' when its key is below m'.
struct LineSet {
  std::vector<std::int32_t> row0, kykz;
  std::vector<std::uint32_t> first_key;  // ascending: line j holds a mode at m' > first_key[j]
  // Line j's keys: kx = 0, 1, ... at keys[right_begin[j], left_begin[j]), then kx = -1,
  // -2, ... up to right_begin[j + 1] (the last entry is keys.size()).
  std::vector<std::size_t> right_begin, left_begin;
  std::vector<std::uint32_t> keys;
};

struct TranslationLines {
  std::size_t max_modes = 0;                            // lines and box hold the first max_modes modes
  std::array<int, 3> box_min{}, box_max{}, box_dims{};  // signed k of node 0; rows padded by 8 nodes
  std::vector<std::complex<float>> weights;  // W_k at box node (kx - min) + dims_x ((ky - min) + dims_y (kz - min))
  LineSet unfolded;                          // every line; key = rank in the mode order
  LineSet folded;                            // empty unless the correlation is real
  std::size_t fold_limit = 0;                // folded lines serve m' <= fold_limit (0: never)
  // For the extras: the FFT grid, the mode order, and the ranks of the unpartnered nodes
  // that the folded lines visit (ascending; at most kMaxUnpairedExtras below fold_limit).
  std::array<std::size_t, 3> dims{};
  std::vector<std::uint32_t> order;
  std::vector<std::uint32_t> unpaired_visited_ranks;
};

// The lines, intervals and extras that sum exactly the first m' modes.
struct LineSelection {
  std::size_t modes = 0;
  bool folded = false;
  std::vector<LineRecord> lines;
  std::vector<ExtraMode> extras;
  std::size_t nodes = 0;  // sum of the interval lengths
};

// The box and both line sets for the first max_modes modes (0: every mode) of `order`
// (mode_order on an FFT grid of `dims`), without weights; the folded set only for a real
// correlation (`conjugate_pairs`).
TranslationLines build_translation_lines(const std::array<std::size_t, 3>& dims, const std::vector<std::size_t>& order,
                                         bool conjugate_pairs, std::size_t max_modes = 0);

// W_k = S1(w_k) S2(-w_k) dw at the box's nodes: the translation-only product.
void fill_translation_weights(TranslationLines& lines, const PairSpectra& spectra);

// Every mode, with the translation-only product. `order` is mode_order(spectra); `fold`
// allows the folded sum (it is used only for a real correlation).
TranslationLines build_translation_lines(const PairSpectra& spectra, const std::vector<std::size_t>& order, bool fold);

// The box node of signed frequency index k.
std::size_t box_node(const TranslationLines& lines, int kx, int ky, int kz);

// Fills `out` for m' = modes (1 <= modes <= lines.max_modes).
void select_lines(const TranslationLines& lines, std::size_t modes, LineSelection& out);

}  // namespace snapfit
