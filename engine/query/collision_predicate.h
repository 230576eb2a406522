#pragma once
// Seed 001's collision predicate (sec. 4.1, eq. 5 and 50) on the truncated Fourier sum.
// With indicator affinities (i 1_S1, i 1_S2) a query's energy is the overlap volume
// g(R, t) = <1_S1, 1_{(R,t)S2}> summed over the m' retained modes; the seed's predicate is
// g > 0. The truncated sum g_m' differs from the sum over every lattice mode by the tail
//     |g - g_m'| = |sum_{k >= m'} S1(w_k) conj S2(R^T w_k) e^{...}| dw
//               <= dw sqrt(sum_{k >= m'} |S1(w_k)|^2) sqrt(sum_{k >= m'} |S2(w_k)|^2)   (Cauchy-Schwarz)
// where the retained modes are a low-pass ball (engine/spectra/mode_order.h), so the same |w| tail
// holds part 2's rotated samples (exact at R = I; for R != I the rotated nodes sample the
// same |w| shell, up to the interpolation). So g_m' > B(m') proves g > 0: the verdict
// "collides" when the truncated overlap exceeds the bound, which is derived from the two
// spectra alone, not fitted to any reference.
#include <cstddef>
#include <vector>

#include "engine/spectra/spectra.h"
#include "snapfit/collision.h"
#include "snapfit/query.h"

namespace snapfit {

TruncationTails truncation_tails(const PairSpectra& spectra);

}  // namespace snapfit
