#pragma once
// Charts as data: lines, points and bars on linear or log axes, with highlighted points
// and reference lines, drawn in the browser by report/web (uPlot) inside report.html and
// the chart pages that `snapfit tune --html` and the benchmarks in perf/ write.
//
// Axis ranges come from the data (series, markers, reference lines) with a margin unless
// fixed. Non-finite values, and non-positive ones on log axes, are not drawn: a line
// breaks there. A chart with nothing to plot still draws its axes, with a "no data" note.
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace snapfit {

struct Series {
  // bars: one bar per point, centred on x, from y = 0 (from the bottom on a log y axis).
  enum class Style { line, points, line_points, bars };
  std::string label;         // legend text
  std::vector<double> x, y;  // the same length
  Style style = Style::line_points;
  std::string color;  // "#rrggbb"; empty: the next colour of the palette
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
  // Fixed axis limits; NaN leaves that end automatic.
  double x_min = std::numeric_limits<double>::quiet_NaN(), x_max = std::numeric_limits<double>::quiet_NaN();
  double y_min = std::numeric_limits<double>::quiet_NaN(), y_max = std::numeric_limits<double>::quiet_NaN();
};

// The chart as the page's JSON spec (report/web/src/charts.js). Series that all share one
// x are written with it once; arrays longer than 256 values go as base64 float32
// (report/page_encoding.h), shorter ones as JSON numbers (null for non-finite ones).
// Throws snapfit::Error for a series whose x and y differ in length, a colour that is not
// "#rrggbb", and fixed limits that are not increasing or not positive on a log axis.
nlohmann::json chart_json(const Chart& chart);

// A histogram of the finite values in `bins` equal bins between their minimum and
// maximum, as one `bars` series labelled "<n> values" with y label "count". No finite
// values give an empty series ("no data"). Throws snapfit::Error for bins outside
// 1..100000.
Chart histogram_chart(const std::string& title, const std::string& x_label, const std::vector<double>& values, int bins,
                      bool log_y = false);

// A self-contained page of charts (report/html_page.h) with a title and lines of notes
// above them (e.g. the command and the machine), written atomically to `path`. Throws
// snapfit::Error as chart_json and write_html_page do.
void write_chart_page(const std::string& path, const std::string& title, const std::vector<std::string>& notes,
                      const std::vector<Chart>& charts);

}  // namespace snapfit
