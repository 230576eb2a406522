#pragma once
// Tick positions and labels for the axes and colour bars of slice figures
// (report/slice_figure.h).
#include <string>
#include <vector>

namespace snapfit {

struct AxisTicks {
  std::vector<double> major;  // labelled
  double step = 0;            // spacing of the ticks
};

// At most max_ticks (>= 2) ticks at multiples of 1, 2 or 5 x 10^k in [lo, hi], the
// finest step that fits: [0, 9.3] with 6 gives 0, 2, 4, 6, 8. lo == hi gives lo alone;
// non-finite bounds give none.
AxisTicks linear_ticks(double lo, double hi, int max_ticks);

// A tick value as text: plain decimals with as many places as `step` (the spacing of
// neighbouring ticks) needs, or a short exponent form ("2e6", "1.5e-5") for very large
// or small numbers.
std::string tick_label(double value, double step);

}  // namespace snapfit
