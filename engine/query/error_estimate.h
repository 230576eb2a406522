#pragma once
// The per-query error estimate (include/snapfit/query.h ErrorEstimate). The retained modes
// are a low-pass ball, so what a query leaves out is the spectrum beyond the cut; the two
// octave bands just below it, modes (m'/4, m'/2] and (m'/2, m'], summed at the query's own
// pose, measure how much the sum still changes there (the kernel returns both bands with
// the total). The estimate is kErrorEstimateScale times their root sum of squares, per
// output. The interpolation error of a rotated spectrum shows in the bands as well, as a
// part of what they change. docs/design.md "Error estimate" has the measurements behind
// the scale and what the estimate covers.
#include "snapfit/query.h"

namespace snapfit {

// The 95th percentile of |error| / sqrt(|band a|^2 + |band b|^2) over 40 poses of the default
// scene's trajectory, at m' = 8,192, 16,384 and 32,768 (tricubic, against the exact-rotation
// reference with every mode): 2.9 to 7.5, median 4.4 over the nine (m', output) cases.
constexpr double kErrorEstimateScale = 4.0;

// The estimate from the band results (each as a query result over that band alone).
ErrorEstimate estimate_error(const QueryResult& band_a, const QueryResult& band_b);

}  // namespace snapfit
