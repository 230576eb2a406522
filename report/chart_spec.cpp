#include "report/chart_spec.h"

#include <algorithm>
#include <cmath>

#include "report/html_page.h"
#include "report/page_encoding.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr std::size_t kInlineValues = 256;

nlohmann::json values_json(const std::vector<double>& values) {
  if (values.size() > kInlineValues) return float32_base64(values);
  nlohmann::json out = nlohmann::json::array();
  for (double v : values) out.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr));
  return out;
}

const char* style_name(Series::Style s) {
  switch (s) {
    case Series::Style::line:
      return "line";
    case Series::Style::points:
      return "points";
    case Series::Style::bars:
      return "bars";
    case Series::Style::line_points:
      break;
  }
  return "line_points";
}

bool is_hex_colour(const std::string& c) {
  return c.size() == 7 && c[0] == '#' &&
         std::all_of(c.begin() + 1, c.end(), [](char h) { return std::isxdigit(static_cast<unsigned char>(h)); });
}

void check_limits(const std::string& who, const char* axis, double lo, double hi, bool log) {
  for (double v : {lo, hi})
    if (!std::isnan(v) && (!std::isfinite(v) || (log && !(v > 0))))
      throw Error(who + ": fixed " + axis + " limit " + std::to_string(v) + " is not " +
                  (log ? "a positive finite number on a log axis" : "finite"));
  if (!std::isnan(lo) && !std::isnan(hi) && !(hi > lo))
    throw Error(who + ": fixed " + axis + " limits [" + std::to_string(lo) + ", " + std::to_string(hi) +
                "] are not increasing");
}

nlohmann::json limit(double v) { return std::isnan(v) ? nlohmann::json(nullptr) : nlohmann::json(v); }

}  // namespace

nlohmann::json chart_json(const Chart& chart) {
  const std::string who = "chart '" + chart.title + "'";
  for (const Series& s : chart.series) {
    if (s.x.size() != s.y.size())
      throw Error(who + ": series '" + s.label + "' has " + std::to_string(s.x.size()) + " x values and " +
                  std::to_string(s.y.size()) + " y values");
    if (!s.color.empty() && !is_hex_colour(s.color))
      throw Error(who + ": series '" + s.label + "' colour '" + s.color + "' is not #rrggbb");
  }
  check_limits(who, "x", chart.x_min, chart.x_max, chart.log_x);
  check_limits(who, "y", chart.y_min, chart.y_max, chart.log_y);

  nlohmann::json j = {{"title", chart.title},        {"x_label", chart.x_label},    {"y_label", chart.y_label},
                      {"log_x", chart.log_x},        {"log_y", chart.log_y},        {"x_min", limit(chart.x_min)},
                      {"x_max", limit(chart.x_max)}, {"y_min", limit(chart.y_min)}, {"y_max", limit(chart.y_max)}};
  const bool shared_x =
      !chart.series.empty() && std::all_of(chart.series.begin(), chart.series.end(),
                                           [&](const Series& s) { return s.x == chart.series.front().x; });
  if (shared_x) j["x"] = values_json(chart.series.front().x);
  nlohmann::json series = nlohmann::json::array();
  for (const Series& s : chart.series) {
    nlohmann::json e = {{"label", s.label}, {"style", style_name(s.style)}, {"y", values_json(s.y)}};
    if (!shared_x) e["x"] = values_json(s.x);
    if (!s.color.empty()) e["color"] = s.color;
    series.push_back(std::move(e));
  }
  j["series"] = std::move(series);
  nlohmann::json markers = nlohmann::json::array(), hlines = nlohmann::json::array();
  for (const Marker& m : chart.markers)
    if (std::isfinite(m.x) && std::isfinite(m.y)) markers.push_back({{"x", m.x}, {"y", m.y}, {"label", m.label}});
  for (const HLine& h : chart.hlines)
    if (std::isfinite(h.y)) hlines.push_back({{"y", h.y}, {"label", h.label}});
  j["markers"] = std::move(markers);
  j["hlines"] = std::move(hlines);
  return j;
}

Chart histogram_chart(const std::string& title, const std::string& x_label, const std::vector<double>& values, int bins,
                      bool log_y) {
  if (bins < 1 || bins > 100000)
    throw Error("histogram" + (title.empty() ? std::string() : " '" + title + "'") + ": bins must be 1..100000, not " +
                std::to_string(bins));
  Chart chart;
  chart.title = title;
  chart.x_label = x_label;
  chart.y_label = "count";
  chart.log_y = log_y;
  Series s;
  s.style = Series::Style::bars;
  double lo = 0, hi = 0;
  std::size_t n = 0;
  for (double v : values)
    if (std::isfinite(v)) {
      lo = n == 0 ? v : std::min(lo, v);
      hi = n == 0 ? v : std::max(hi, v);
      ++n;
    }
  const std::size_t skipped = values.size() - n;
  s.label = std::to_string(n) + " values" + (skipped ? " (" + std::to_string(skipped) + " not finite)" : "");
  if (n > 0) {
    if (lo == hi) {
      lo -= 0.5;
      hi += 0.5;
    }
    // Halves keep hi - lo finite for values near the double limit.
    const double half_span = 0.5 * hi - 0.5 * lo;
    std::vector<double> counts(static_cast<std::size_t>(bins), 0.0);
    for (double v : values)
      if (std::isfinite(v)) {
        const double t = (0.5 * v - 0.5 * lo) / half_span;
        counts[static_cast<std::size_t>(std::clamp(static_cast<int>(t * bins), 0, bins - 1))] += 1;
      }
    for (int b = 0; b < bins; ++b) {
      const double f = (b + 0.5) / bins;
      s.x.push_back(lo * (1 - f) + hi * f);
      s.y.push_back(counts[static_cast<std::size_t>(b)]);
    }
  }
  chart.series.push_back(std::move(s));
  return chart;
}

void write_chart_page(const std::string& path, const std::string& title, const std::vector<std::string>& notes,
                      const std::vector<Chart>& charts) {
  nlohmann::json specs = nlohmann::json::array();
  for (const Chart& c : charts) specs.push_back(chart_json(c));
  write_html_page(path, "chart_page", title,
                  {{"kind", "charts"}, {"title", title}, {"notes", notes}, {"charts", specs}});
}

}  // namespace snapfit
