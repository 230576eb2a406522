#pragma once
// Small charts rendered to PNG for benchmark and run reports: lines, points and bars on
// linear or log axes, with ticks, labels, a title, a legend, highlighted points and
// dashed reference lines. No dependencies beyond io/png_export.h and the built-in
// bitmap font (report/bitmap_font.h).
//
// Layout: white background; the plot area is framed; "nice" ticks (1-2-5 steps on
// linear axes, decades with minor ticks at 2..9 on log axes) with light grid lines;
// tick labels, axis labels (the y label turned a quarter left) and the title outside
// it; the legend inside it, in the corner that covers the least data. Axis ranges come
// from the data (series, markers, reference lines) with a 5% margin unless fixed.
// Non-finite values, and non-positive ones on log axes, are skipped: a line breaks
// there. A chart with nothing to plot still draws its axes, with a "no data" note.
#include <array>
#include <limits>
#include <string>
#include <vector>

#include "io/png_export.h"

namespace snapfit {

struct Series {
  // bars: one bar per point, centred on x, as wide as the closest spacing of the x
  // values allows, from y = 0 (from the bottom of the plot area on a log y axis).
  enum class Style { line, points, line_points, bars };
  std::string label;         // legend text; series with no label are left out of the legend
  std::vector<double> x, y;  // the same length
  Style style = Style::line_points;
  std::array<unsigned char, 3> color = {0, 0, 0};  // {0, 0, 0}: next colour of the palette
};

// A highlighted point (e.g. "chosen"), drawn as a ring with its label beside it.
struct Marker {
  double x = 0, y = 0;
  std::string label;
};

// A horizontal reference line (e.g. the 1 ms budget), dashed, labelled at its right end.
struct HLine {
  double y = 0;
  std::string label;
};

struct Chart {
  std::string title, x_label, y_label;
  bool log_x = false, log_y = false;
  std::vector<Series> series;
  std::vector<Marker> markers;
  std::vector<HLine> hlines;
  int width = 800, height = 500;  // pixels, 100..8000 each
  // Fixed axis limits; NaN leaves that end automatic.
  double x_min = std::numeric_limits<double>::quiet_NaN(), x_max = std::numeric_limits<double>::quiet_NaN();
  double y_min = std::numeric_limits<double>::quiet_NaN(), y_max = std::numeric_limits<double>::quiet_NaN();
  int text_scale = 0;  // font pixel size 1..8; 0: 1, or 2 from 1600 x 1000 up
};

// The chart drawn as RGB pixels (value_min/value_max are left 0). Throws snapfit::Error
// for a side outside 100..8000, a series whose x and y differ in length, a text_scale
// outside 0..8, and fixed limits that are not finite, not increasing, or not positive
// on a log axis.
SliceImage render_chart(const Chart& chart);

// render_chart written as a PNG (atomically, through write_png) with tEXt "Title" and
// "Software". Throws snapfit::Error as render_chart and write_png do.
void write_chart_png(const std::string& path, const Chart& chart);

// A histogram of the finite values in `bins` equal bins between their minimum and
// maximum, as one `bars` series labelled "<n> values" with y label "count". A log y
// axis leaves empty bins out. No finite values give an empty series ("no data").
// Throws snapfit::Error for bins outside 1..100000.
Chart histogram_chart(const std::string& title, const std::string& x_label, const std::vector<double>& values, int bins,
                      bool log_y = false);

// --- The pieces render_chart is built from, for callers that overlay or test.

struct AxisTicks {
  std::vector<double> major;  // labelled, with a grid line
  std::vector<double> minor;  // a short tick (and a faint grid line on log axes)
  double step = 0;            // spacing of evenly spaced majors; 0: each labelled on its own (log)
};

// At most max_ticks (>= 2) major ticks at multiples of 1, 2 or 5 x 10^k in [lo, hi],
// the finest step that fits: [0, 9.3] with 6 gives 0, 2, 4, 6, 8. No minor ticks.
AxisTicks linear_ticks(double lo, double hi, int max_ticks);

// Ticks for a log axis over [lo, hi] (0 < lo < hi): the decades 10^k inside, every
// one with minor ticks at 2..9 x 10^k, or every 2nd, 3rd, 5th, ... when there are more
// than max_ticks (the others become minor). Under two decades inside, 1, 2 and 5 x
// 10^k; under two of those, linear_ticks. [3, 4000] gives 10, 100, 1000.
AxisTicks log_ticks(double lo, double hi, int max_ticks);

// A tick value as text: plain decimals with as many places as `step` (the spacing of
// neighbouring ticks) needs, or a short exponent form ("2e6", "1.5e-5") for very large
// or small numbers.
std::string tick_label(double value, double step);

// Where render_chart puts things.
struct ChartLayout {
  int left = 0, top = 0, right = 0, bottom = 0;   // plot area, inclusive pixel bounds
  double x_lo = 0, x_hi = 1, y_lo = 0, y_hi = 1;  // the data range shown
  bool log_x = false, log_y = false;
  AxisTicks x_ticks, y_ticks;
  int text_scale = 1;
  bool has_data = false;  // some series point is plotted
};

// Validates `chart` as render_chart does and lays it out.
ChartLayout chart_layout(const Chart& chart);

// Data to pixel coordinates (column, row; fractional, rounded when drawn): lo maps to
// left / bottom, hi to right / top. NaN for non-finite values and non-positive ones on
// a log axis.
double pixel_x(const ChartLayout& layout, double x);
double pixel_y(const ChartLayout& layout, double y);

}  // namespace snapfit
