// Charts rendered to RGB images and PNG (report/plot.h).
#include "report/plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "report/bitmap_font.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

using Rgb = std::array<unsigned char, 3>;

constexpr Rgb kWhite = {255, 255, 255};
constexpr Rgb kGrid = {224, 224, 224};
constexpr Rgb kGridMinor = {242, 242, 242};
constexpr Rgb kFrame = {70, 70, 70};
constexpr Rgb kText = {40, 40, 40};
constexpr Rgb kNote = {150, 150, 150};
constexpr Rgb kReference = {105, 105, 105};
constexpr Rgb kRing = {20, 20, 20};
constexpr Rgb kLegendBorder = {175, 175, 175};

// Tableau 10, the usual qualitative palette.
constexpr Rgb kPalette[10] = {{31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
                              {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207}};

constexpr double kHuge = 4.0e307;  // axis ranges are kept within +-kHuge so spans stay finite

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

std::string chart_name(const Chart& chart) { return chart.title.empty() ? "chart" : "chart '" + chart.title + "'"; }

// --- Validation

void check_limits(const Chart& chart, double lo, double hi, bool log, const char* axis) {
  const std::string who = chart_name(chart) + ": " + axis + " axis limit ";
  for (double v : {lo, hi})
    if (!std::isnan(v) && (!std::isfinite(v) || (log && v <= 0)))
      throw Error(who + num(v) +
                  (log ? " is not a positive finite number (the axis is logarithmic)" : " is not finite"));
  if (!std::isnan(lo) && !std::isnan(hi) && !(lo < hi))
    throw Error(who + "range [" + num(lo) + ", " + num(hi) + "] is empty: the minimum must be below the maximum");
}

void validate(const Chart& chart) {
  const std::string who = chart_name(chart);
  if (chart.width < 100 || chart.width > 8000 || chart.height < 100 || chart.height > 8000)
    throw Error(who + ": size " + std::to_string(chart.width) + " x " + std::to_string(chart.height) +
                " is outside 100..8000 pixels per side");
  if (chart.text_scale < 0 || chart.text_scale > 8)
    throw Error(who + ": text scale " + std::to_string(chart.text_scale) + " is outside 0..8 (0 = automatic)");
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const Series& s = chart.series[i];
    if (s.x.size() != s.y.size())
      throw Error(who + ": series " + std::to_string(i) + (s.label.empty() ? "" : " '" + s.label + "'") + " has " +
                  std::to_string(s.x.size()) + " x values but " + std::to_string(s.y.size()) + " y values");
  }
  check_limits(chart, chart.x_min, chart.x_max, chart.log_x, "x");
  check_limits(chart, chart.y_min, chart.y_max, chart.log_y, "y");
}

// --- Axis ranges (in axis units: log10 of the value on log axes)

// NaN for values a (log) axis cannot show.
double axis_value(double v, bool log) {
  if (!std::isfinite(v) || (log && !(v > 0))) return std::nan("");
  return log ? std::log10(v) : v;
}

double from_axis(double a, bool log) { return log ? std::pow(10.0, a) : a; }

struct Extent {
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  bool any() const { return lo <= hi; }
  void add(double v) {
    if (std::isnan(v)) return;
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
};

// The shown range [lo, hi] in axis units: the extent with a 5% margin (none on a side
// pinned at a bar baseline), then fixed limits.
std::pair<double, double> axis_range(Extent e, bool pin_lo, bool pin_hi, bool log, double fixed_min, double fixed_max) {
  double lo = 0, hi = 1;
  if (e.any()) {
    lo = std::clamp(e.lo, -kHuge, kHuge);
    hi = std::clamp(e.hi, -kHuge, kHuge);
    if (lo == hi) {
      const double d = log ? 0.5 : (lo == 0 ? 1.0 : std::abs(lo) * 0.1);
      lo -= d;
      hi += d;
    } else {
      const double pad = 0.05 * hi - 0.05 * lo;
      if (!pin_lo) lo -= pad;
      if (!pin_hi) hi += pad;
    }
  }
  const double fmin = axis_value(fixed_min, log), fmax = axis_value(fixed_max, log);
  if (!std::isnan(fmin)) lo = fmin;
  if (!std::isnan(fmax)) hi = fmax;
  if (!(hi > lo)) {
    if (!std::isnan(fmax) && std::isnan(fmin))
      lo = hi - (log ? 1.0 : std::max(1.0, std::abs(hi)));
    else
      hi = lo + (log ? 1.0 : std::max(1.0, std::abs(lo)));
  }
  return {std::clamp(lo, -kHuge, kHuge), std::clamp(hi, -kHuge, kHuge)};
}

double pow10(int k) { return std::pow(10.0, k); }

// The labels of an axis's major ticks.
std::vector<std::string> tick_labels(const AxisTicks& t) {
  std::vector<std::string> out;
  for (double v : t.major) out.push_back(tick_label(v, t.step));
  return out;
}

int widest(const std::vector<std::string>& texts, int scale) {
  int w = 0;
  for (const auto& s : texts) w = std::max(w, text_width(s, scale));
  return w;
}

// Smallest positive gap between sorted values; 0 when there is none.
double min_gap(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  double gap = 0;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (v[i] > v[i - 1] && (gap == 0 || v[i] - v[i - 1] < gap)) gap = v[i] - v[i - 1];
  return gap;
}

// --- Raster primitives; every one draws only inside `clip` (inclusive pixel bounds).

// Nearest pixel index; far-off coordinates are pulled in to +-1e6 first so the
// conversion never overflows (the chart is at most 8000 pixels wide).
int to_pixel(double v) { return static_cast<int>(std::lround(std::clamp(v, -1e6, 1e6))); }

struct Box {
  int x0, y0, x1, y1;
};

void put(SliceImage& im, const Box& clip, int x, int y, const Rgb& c) {
  if (x < clip.x0 || x > clip.x1 || y < clip.y0 || y > clip.y1 || x < 0 || y < 0 || x >= im.width || y >= im.height)
    return;
  std::memcpy(im.rgb.data() + 3 * (static_cast<std::size_t>(y) * im.width + x), c.data(), 3);
}

Rgb get(const SliceImage& im, int x, int y) {
  const unsigned char* p = im.rgb.data() + 3 * (static_cast<std::size_t>(y) * im.width + x);
  return {p[0], p[1], p[2]};
}

void fill_rect(SliceImage& im, const Box& clip, int x0, int y0, int x1, int y1, const Rgb& c) {
  if (x0 > x1) std::swap(x0, x1);
  if (y0 > y1) std::swap(y0, y1);
  x0 = std::max(x0, clip.x0);
  x1 = std::min(x1, clip.x1);
  y0 = std::max(y0, clip.y0);
  y1 = std::min(y1, clip.y1);
  for (int y = y0; y <= y1; ++y)
    for (int x = x0; x <= x1; ++x) put(im, clip, x, y, c);
}

// A thick x thick square around (x, y).
void stamp(SliceImage& im, const Box& clip, int x, int y, const Rgb& c, int thick) {
  const int a = -(thick - 1) / 2;
  for (int dy = a; dy < a + thick; ++dy)
    for (int dx = a; dx < a + thick; ++dx) put(im, clip, x + dx, y + dy, c);
}

// Liang-Barsky: shortens the segment to the rectangle; false when nothing is left.
bool clip_segment(double& x0, double& y0, double& x1, double& y1, double xmin, double ymin, double xmax, double ymax) {
  const double dx = x1 - x0, dy = y1 - y0;
  double t0 = 0, t1 = 1;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {x0 - xmin, xmax - x0, y0 - ymin, ymax - y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0) {
      if (q[i] < 0) return false;  // parallel and outside
      continue;
    }
    const double r = q[i] / p[i];
    if (p[i] < 0)
      t0 = std::max(t0, r);
    else
      t1 = std::min(t1, r);
    if (t0 > t1) return false;
  }
  const double ax = x0 + t0 * dx, ay = y0 + t0 * dy, bx = x0 + t1 * dx, by = y0 + t1 * dy;
  x0 = ax;
  y0 = ay;
  x1 = bx;
  y1 = by;
  return true;
}

// A segment between pixel coordinates, clipped first (Liang-Barsky) and then drawn
// with Bresenham's steps, each stamped thick x thick.
void draw_line(SliceImage& im, const Box& clip, double x0, double y0, double x1, double y1, const Rgb& c, int thick) {
  for (double v : {x0, y0, x1, y1})
    if (!std::isfinite(v)) return;
  if (!clip_segment(x0, y0, x1, y1, clip.x0 - 0.5, clip.y0 - 0.5, clip.x1 + 0.5, clip.y1 + 0.5)) return;
  int ax = to_pixel(x0), ay = to_pixel(y0);
  const int bx = to_pixel(x1), by = to_pixel(y1);
  const int dx = std::abs(bx - ax), dy = -std::abs(by - ay);
  const int sx = ax < bx ? 1 : -1, sy = ay < by ? 1 : -1;
  int err = dx + dy;
  for (;;) {
    stamp(im, clip, ax, ay, c, thick);
    if (ax == bx && ay == by) break;
    const int e2 = 2 * err;
    if (e2 >= dy) {
      err += dy;
      ax += sx;
    }
    if (e2 <= dx) {
      err += dx;
      ay += sy;
    }
  }
}

void draw_disc(SliceImage& im, const Box& clip, double cx, double cy, int r, const Rgb& c) {
  if (!std::isfinite(cx) || !std::isfinite(cy)) return;
  const int x = to_pixel(cx), y = to_pixel(cy);
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx)
      if (dx * dx + dy * dy <= r * r + r) put(im, clip, x + dx, y + dy, c);
}

void draw_ring(SliceImage& im, const Box& clip, double cx, double cy, int r, int thick, const Rgb& c) {
  if (!std::isfinite(cx) || !std::isfinite(cy)) return;
  const int x = to_pixel(cx), y = to_pixel(cy);
  const int reach = r + thick;
  for (int dy = -reach; dy <= reach; ++dy)
    for (int dx = -reach; dx <= reach; ++dx)
      if (const double d = std::sqrt(double(dx * dx + dy * dy)); d >= r - 0.5 * thick && d < r + 0.5 * thick)
        put(im, clip, x + dx, y + dy, c);
}

// Text over data: a one-pixel white outline keeps it readable.
void draw_halo_text(SliceImage& im, int x, int y, const std::string& text, const Rgb& c, int scale) {
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx)
      if (dx != 0 || dy != 0) draw_text(im, x + dx, y + dy, text, kWhite, scale);
  draw_text(im, x, y, text, c, scale);
}

// Pixels in the box (clipped to `within`) that hold something other than background
// and grid: how much a legend placed there would hide.
long ink_in(const SliceImage& im, const Box& b, const Box& within) {
  long n = 0;
  for (int y = std::max(b.y0, within.y0); y <= std::min(b.y1, within.y1); ++y)
    for (int x = std::max(b.x0, within.x0); x <= std::min(b.x1, within.x1); ++x) {
      const Rgb c = get(im, x, y);
      if (c != kWhite && c != kGrid && c != kGridMinor) ++n;
    }
  return n;
}

// Of the top-left corners offered for a w x h label, the first of those hiding the
// least ink, preferring spots wholly inside `within`.
std::pair<int, int> quietest_spot(const SliceImage& im, const std::vector<std::pair<int, int>>& spots, int w, int h,
                                  const Box& within) {
  std::pair<int, int> best = spots.front();
  long least = -1;
  for (const auto& [x, y] : spots) {
    const bool inside = x - 1 >= within.x0 && y - 1 >= within.y0 && x + w <= within.x1 && y + h <= within.y1;
    const long score = ink_in(im, {x - 1, y - 1, x + w, y + h}, within) + (inside ? 0 : 1L << 40);
    if (least < 0 || score < least) {
      least = score;
      best = {x, y};
    }
  }
  return best;
}

Rgb series_color(const Chart& chart, std::size_t i) {
  const Rgb& c = chart.series[i].color;
  return c == Rgb{0, 0, 0} ? kPalette[i % 10] : c;
}

// --- Layout sizes, all proportional to the text scale s.
int pad_of(int s) { return 8 * s; }
int tick_of(int s) { return 5 * s; }

}  // namespace

// --- Ticks

AxisTicks linear_ticks(double lo, double hi, int max_ticks) {
  AxisTicks t;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(hi - lo)) return t;
  if (!(hi > lo)) {
    t.major.push_back(lo);
    return t;
  }
  max_ticks = std::max(max_ticks, 2);
  const double base = std::pow(10.0, std::floor(std::log10((hi - lo) / max_ticks)));
  double step = base;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * base;
    const double n = std::floor(hi / step + 1e-9) - std::ceil(lo / step - 1e-9) + 1;
    if (n <= max_ticks) break;
  }
  t.step = step;
  const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
  for (double k = k0; k <= k1 && t.major.size() < 1000; ++k) t.major.push_back(k == 0 ? 0.0 : k * step);
  return t;
}

AxisTicks log_ticks(double lo, double hi, int max_ticks) {
  if (!(lo > 0) || !(hi > lo) || !std::isfinite(hi)) return linear_ticks(lo, hi, max_ticks);
  max_ticks = std::max(max_ticks, 2);
  const double slack = 1e-9;
  auto inside = [&](double v) { return v >= lo * (1 - slack) && v <= hi * (1 + slack); };
  const int k0 = static_cast<int>(std::ceil(std::log10(lo) - slack));
  const int k1 = static_cast<int>(std::floor(std::log10(hi) + slack));
  AxisTicks t;
  if (k1 - k0 + 1 >= 2) {
    // Every s-th decade labelled; the others, and 2..9 x 10^k when s = 1, minor.
    int s = 1;
    auto multiples = [&](int step) {
      int n = 0;
      for (int k = k0; k <= k1; ++k) n += (k % step == 0);
      return n;
    };
    for (int step : {1, 2, 3, 4, 5, 10, 20, 25, 50, 100, 200}) {
      s = step;
      if (multiples(step) <= max_ticks && multiples(step) >= 1) break;
    }
    for (int k = k0; k <= k1; ++k) (k % s == 0 ? t.major : t.minor).push_back(pow10(k));
    if (s == 1)
      for (int k = k0 - 1; k <= k1; ++k)
        for (int m = 2; m <= 9; ++m)
          if (inside(m * pow10(k))) t.minor.push_back(m * pow10(k));
    std::sort(t.minor.begin(), t.minor.end());
    return t;
  }
  // Within about a decade: 1, 2, 5 x 10^k labelled, 3, 4, 6..9 x 10^k minor.
  for (int k = k0 - 1; k <= k1; ++k)
    for (int m = 1; m <= 9; ++m) {
      const double v = m * pow10(k);
      if (inside(v)) (m == 1 || m == 2 || m == 5 ? t.major : t.minor).push_back(v);
    }
  if (t.major.size() >= 2 && static_cast<int>(t.major.size()) <= max_ticks) return t;
  return linear_ticks(lo, hi, max_ticks);
}

std::string tick_label(double value, double step) {
  if (!std::isfinite(value)) return num(value);
  step = std::abs(step);
  if (!(step > 0) || !std::isfinite(step)) step = std::abs(value);
  if (std::abs(value) < step * 1e-9 || value == 0) return "0";
  const int e = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  const double mag = std::abs(value);
  char buf[64];
  if (mag < 1e6 && step >= 1e-4) {
    int decimals = std::max(0, -e);
    // Steps like 0.25 need a place more than their exponent says.
    while (decimals < 12) {
      const double scaled = step * std::pow(10.0, decimals);
      if (std::abs(scaled - std::round(scaled)) <= 1e-6 * scaled) break;
      ++decimals;
    }
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
  }
  // Exponent form with as many mantissa places as the step needs: "1.5e-5", "2e6".
  const int places = std::clamp(static_cast<int>(std::floor(std::log10(mag) + 1e-9)) - e, 0, 12);
  std::snprintf(buf, sizeof buf, "%.*e", places, value);
  std::string text = buf;
  const std::size_t at = text.find('e');
  std::string mantissa = text.substr(0, at), exponent = text.substr(at + 1);
  const bool negative = exponent[0] == '-';
  exponent = exponent.substr(1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

// --- Layout

ChartLayout chart_layout(const Chart& chart) {
  validate(chart);
  ChartLayout L;
  L.log_x = chart.log_x;
  L.log_y = chart.log_y;

  // Extents of everything that will be drawn.
  Extent ex, ey;
  bool bars = false;
  for (const Series& s : chart.series) {
    Extent shown;               // x of the points drawn
    std::vector<double> all_x;  // x of every point with a valid x: bar widths
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      const double ax = axis_value(s.x[i], chart.log_x), ay = axis_value(s.y[i], chart.log_y);
      if (!std::isnan(ax)) all_x.push_back(ax);
      if (std::isnan(ax) || std::isnan(ay)) continue;
      shown.add(ax);
      ey.add(ay);
      L.has_data = true;
    }
    if (!shown.any()) continue;
    ex.add(shown.lo);
    ex.add(shown.hi);
    if (s.style == Series::Style::bars) {
      bars = true;
      const double half = 0.5 * min_gap(all_x);  // whole bars in view
      ex.add(shown.lo - half);
      ex.add(shown.hi + half);
    }
  }
  // Linear bars start at 0: keep it in view, with no margin beyond it.
  const bool pin_lo = bars && !chart.log_y && ey.any() && ey.lo >= 0;
  const bool pin_hi = bars && !chart.log_y && ey.any() && ey.hi <= 0;
  if (bars && !chart.log_y) ey.add(0.0);
  for (const Marker& m : chart.markers) {
    const double ax = axis_value(m.x, chart.log_x), ay = axis_value(m.y, chart.log_y);
    if (std::isnan(ax) || std::isnan(ay)) continue;
    ex.add(ax);
    ey.add(ay);
  }
  for (const HLine& h : chart.hlines) ey.add(axis_value(h.y, chart.log_y));

  const auto [xa, xb] = axis_range(ex, false, false, chart.log_x, chart.x_min, chart.x_max);
  const auto [ya, yb] = axis_range(ey, pin_lo, pin_hi, chart.log_y, chart.y_min, chart.y_max);
  L.x_lo = from_axis(xa, chart.log_x);
  L.x_hi = from_axis(xb, chart.log_x);
  L.y_lo = from_axis(ya, chart.log_y);
  L.y_hi = from_axis(yb, chart.log_y);

  auto ticks = [](double lo, double hi, bool log, int n) {
    return log ? log_ticks(lo, hi, n) : linear_ticks(lo, hi, n);
  };

  // The largest text scale up to the requested one that leaves a usable plot area.
  int s = chart.text_scale > 0 ? chart.text_scale : (chart.width >= 1600 && chart.height >= 1000 ? 2 : 1);
  for (;; --s) {
    const int pad = pad_of(s), tick = tick_of(s), th = text_height(s);
    L.text_scale = s;
    L.top = pad + (chart.title.empty() ? 0 : text_height(s + 1) + pad) + 4 * s;
    L.bottom = chart.height - 1 - (s + tick + 3 * s + th + (chart.x_label.empty() ? 0 : 6 * s + th) + pad);
    const int plot_h = L.bottom - L.top;
    L.y_ticks = ticks(L.y_lo, L.y_hi, chart.log_y, std::max(2, plot_h / (50 * s)));
    L.left = pad + (chart.y_label.empty() ? 0 : th + 6 * s) + widest(tick_labels(L.y_ticks), s) + 3 * s + tick + s;
    L.right = chart.width - 1 - 3 * pad;
    const int plot_w = L.right - L.left;
    // As many x ticks as fit without their labels touching.
    for (int n = std::max(2, plot_w / (80 * s));; --n) {
      L.x_ticks = ticks(L.x_lo, L.x_hi, chart.log_x, n);
      const int need = static_cast<int>(L.x_ticks.major.size()) * (widest(tick_labels(L.x_ticks), s) + 12 * s);
      if (need <= plot_w || n <= 2) break;
    }
    if ((plot_w >= 40 && plot_h >= 40) || s == 1) break;
  }
  L.right = std::max(L.right, L.left + 1);
  L.bottom = std::max(L.bottom, L.top + 1);
  return L;
}

double pixel_x(const ChartLayout& L, double x) {
  const double a = axis_value(x, L.log_x), lo = axis_value(L.x_lo, L.log_x), hi = axis_value(L.x_hi, L.log_x);
  return L.left + (a - lo) / (hi - lo) * (L.right - L.left);
}

double pixel_y(const ChartLayout& L, double y) {
  const double a = axis_value(y, L.log_y), lo = axis_value(L.y_lo, L.log_y), hi = axis_value(L.y_hi, L.log_y);
  return L.bottom - (a - lo) / (hi - lo) * (L.bottom - L.top);
}

// --- Rendering

SliceImage render_chart(const Chart& chart) {
  const ChartLayout L = chart_layout(chart);
  const int s = L.text_scale, pad = pad_of(s), tick = tick_of(s), th = text_height(s);
  SliceImage im;
  im.width = chart.width;
  im.height = chart.height;
  im.rgb.assign(3 * static_cast<std::size_t>(im.width) * static_cast<std::size_t>(im.height), 255);
  const Box all{0, 0, im.width - 1, im.height - 1};
  const Box plot{L.left, L.top, L.right, L.bottom};
  auto in_x = [&](double px) { return px >= L.left - 0.5 && px <= L.right + 0.5; };
  auto in_y = [&](double py) { return py >= L.top - 0.5 && py <= L.bottom + 0.5; };
  auto col = to_pixel;

  // Grid: faint lines at log minor ticks, light ones at major ticks.
  for (int pass = 0; pass < 2; ++pass) {
    const Rgb& c = pass == 0 ? kGridMinor : kGrid;
    for (double v : pass == 0 ? L.x_ticks.minor : L.x_ticks.major)
      if ((pass == 1 || L.log_x) && in_x(pixel_x(L, v)))
        fill_rect(im, plot, col(pixel_x(L, v)), L.top, col(pixel_x(L, v)), L.bottom, c);
    for (double v : pass == 0 ? L.y_ticks.minor : L.y_ticks.major)
      if ((pass == 1 || L.log_y) && in_y(pixel_y(L, v)))
        fill_rect(im, plot, L.left, col(pixel_y(L, v)), L.right, col(pixel_y(L, v)), c);
  }

  // Bars under everything else.
  for (std::size_t i = 0; i < chart.series.size(); ++i) {
    const Series& se = chart.series[i];
    if (se.style != Series::Style::bars) continue;
    std::vector<double> xs;
    for (std::size_t k = 0; k < se.x.size(); ++k)
      if (!std::isnan(pixel_x(L, se.x[k]))) xs.push_back(pixel_x(L, se.x[k]));
    const double gap = min_gap(xs);
    const double half = gap > 0 ? 0.5 * gap : 0.05 * (L.right - L.left);
    const double base = L.log_y ? L.bottom + 0.5 : std::clamp(pixel_y(L, 0.0), L.top - 0.5, L.bottom + 0.5);
    for (std::size_t k = 0; k < se.x.size(); ++k) {
      const double px = pixel_x(L, se.x[k]), py = pixel_y(L, se.y[k]);
      if (std::isnan(px) || std::isnan(py)) continue;
      const int c0 = col(px - half) + (2 * half >= 5 ? 1 : 0);  // a white column between bars
      const int c1 = std::max(c0, col(px + half) - 1);
      fill_rect(im, plot, c0, col(py), c1, col(base), series_color(chart, i));
    }
  }

  // Lines, then points on top.
  for (int pass = 0; pass < 2; ++pass)
    for (std::size_t i = 0; i < chart.series.size(); ++i) {
      const Series& se = chart.series[i];
      const Rgb c = series_color(chart, i);
      const bool lines = se.style == Series::Style::line || se.style == Series::Style::line_points;
      const bool points = se.style == Series::Style::points || se.style == Series::Style::line_points;
      for (std::size_t k = 0; k < se.x.size(); ++k) {
        const double px = pixel_x(L, se.x[k]), py = pixel_y(L, se.y[k]);
        if (pass == 0 && lines && k > 0)
          draw_line(im, plot, pixel_x(L, se.x[k - 1]), pixel_y(L, se.y[k - 1]), px, py, c, 2 * s);
        if (pass == 1 && points) draw_disc(im, plot, px, py, 3 * s, c);
      }
    }

  // Reference lines, dashed.
  for (const HLine& h : chart.hlines) {
    const double py = pixel_y(L, h.y);
    if (std::isnan(py) || !in_y(py)) continue;
    for (int x = L.left; x <= L.right; ++x)
      if ((x - L.left) % (13 * s) < 8 * s) stamp(im, plot, x, col(py), kReference, 2 * s);
  }

  // Highlighted points.
  for (const Marker& m : chart.markers) draw_ring(im, plot, pixel_x(L, m.x), pixel_y(L, m.y), 7 * s, 2 * s, kRing);

  // Frame just outside the plot area, ticks pointing out, tick labels.
  fill_rect(im, all, L.left - s, L.top - s, L.right + s, L.top - 1, kFrame);
  fill_rect(im, all, L.left - s, L.bottom + 1, L.right + s, L.bottom + s, kFrame);
  fill_rect(im, all, L.left - s, L.top, L.left - 1, L.bottom, kFrame);
  fill_rect(im, all, L.right + 1, L.top, L.right + s, L.bottom, kFrame);
  for (int major = 0; major < 2; ++major) {
    const int len = major ? tick : (tick + 1) / 2;
    for (double v : major ? L.x_ticks.major : L.x_ticks.minor) {
      const double px = pixel_x(L, v);
      if (!in_x(px)) continue;
      fill_rect(im, all, col(px) - (s - 1) / 2, L.bottom + s + 1, col(px) + s / 2, L.bottom + s + len, kFrame);
      if (!major) continue;
      const std::string text = tick_label(v, L.x_ticks.step);
      const int w = text_width(text, s);
      draw_text(im, std::clamp(col(px) - w / 2, 0, im.width - w), L.bottom + s + tick + 3 * s, text, kText, s);
    }
    for (double v : major ? L.y_ticks.major : L.y_ticks.minor) {
      const double py = pixel_y(L, v);
      if (!in_y(py)) continue;
      fill_rect(im, all, L.left - s - len, col(py) - (s - 1) / 2, L.left - s - 1, col(py) + s / 2, kFrame);
      if (!major) continue;
      const std::string text = tick_label(v, L.y_ticks.step);
      const int x = L.left - s - tick - 3 * s - text_width(text, s);
      draw_text(im, x, std::clamp(col(py) - 7 * s / 2, 0, im.height - th), text, kText, s);
    }
  }

  // Axis labels and title.
  const int plot_mid_x = (L.left + L.right) / 2, plot_mid_y = (L.top + L.bottom) / 2;
  if (!chart.x_label.empty()) {
    const int w = text_width(chart.x_label, s);
    draw_text(im, std::max(0, plot_mid_x - w / 2), L.bottom + s + tick + 3 * s + th + 6 * s, chart.x_label, kText, s);
  }
  if (!chart.y_label.empty()) {
    const int w = text_width(chart.y_label, s);
    draw_text(im, pad, std::max(0, plot_mid_y - w / 2), chart.y_label, kText, s, true);
  }
  if (!chart.title.empty()) {
    const int ts = text_width(chart.title, s + 1) <= im.width - 2 * pad ? s + 1 : s;  // smaller when too long
    const int w = text_width(chart.title, ts);
    draw_text(im, std::clamp(plot_mid_x - w / 2, 0, std::max(0, im.width - w)),
              pad + text_height(s + 1) - text_height(ts), chart.title, kText, ts);
  }

  // Labels of reference lines (at either end, above or below) and of markers (around
  // the ring), each where it hides the least.
  for (const HLine& h : chart.hlines) {
    const double py = pixel_y(L, h.y);
    if (h.label.empty() || std::isnan(py) || !in_y(py)) continue;
    const int w = text_width(h.label, s), row = col(py);
    const int right = L.right - 4 * s - w, left = L.left + 4 * s;
    const int above = row - 2 * s - th + 1, below = row + 4 * s;
    const auto [x, y] = quietest_spot(im, {{right, above}, {left, above}, {right, below}, {left, below}}, w, th, plot);
    draw_halo_text(im, x, y, h.label, kReference, s);
  }
  for (const Marker& m : chart.markers) {
    const double px = pixel_x(L, m.x), py = pixel_y(L, m.y);
    if (m.label.empty() || std::isnan(px) || std::isnan(py) || !in_x(px) || !in_y(py)) continue;
    const int w = text_width(m.label, s), r = 7 * s + 4 * s, d = r * 7 / 10;
    const int cx = col(px), cy = col(py), mid = cy - 7 * s / 2;
    const auto [x, y] = quietest_spot(im,
                                      {{cx + d, cy - d - th},
                                       {cx + r, mid},
                                       {cx + d, cy + d},
                                       {cx - d - w, cy - d - th},
                                       {cx - r - w, mid},
                                       {cx - d - w, cy + d},
                                       {cx - w / 2, cy - r - th},
                                       {cx - w / 2, cy + r}},
                                      w, th, plot);
    draw_halo_text(im, x, y, m.label, kText, s);
  }

  // Legend in the corner that hides the least.
  std::vector<std::size_t> entries;
  for (std::size_t i = 0; i < chart.series.size(); ++i)
    if (!chart.series[i].label.empty()) entries.push_back(i);
  if (!entries.empty()) {
    const int ip = 6 * s, sw = 22 * s, row = th + 4 * s;
    int text_w = 0;
    for (std::size_t i : entries) text_w = std::max(text_w, text_width(chart.series[i].label, s));
    const int w = ip + sw + ip + text_w + ip, h = 2 * ip + static_cast<int>(entries.size()) * row - 4 * s;
    const int inset = 8 * s;
    const Box corners[4] = {{L.right - inset - w + 1, L.top + inset, L.right - inset, L.top + inset + h - 1},
                            {L.left + inset, L.top + inset, L.left + inset + w - 1, L.top + inset + h - 1},
                            {L.right - inset - w + 1, L.bottom - inset - h + 1, L.right - inset, L.bottom - inset},
                            {L.left + inset, L.bottom - inset - h + 1, L.left + inset + w - 1, L.bottom - inset}};
    Box b = corners[0];
    long least = ink_in(im, b, plot);
    for (const Box& c : corners)
      if (const long n = ink_in(im, c, plot); n < least) {
        least = n;
        b = c;
      }
    fill_rect(im, all, b.x0, b.y0, b.x1, b.y1, kLegendBorder);
    fill_rect(im, all, b.x0 + 1, b.y0 + 1, b.x1 - 1, b.y1 - 1, kWhite);
    for (std::size_t e = 0; e < entries.size(); ++e) {
      const Series& se = chart.series[entries[e]];
      const Rgb c = series_color(chart, entries[e]);
      const int x = b.x0 + ip, y = b.y0 + ip + static_cast<int>(e) * row, mid = y + 7 * s / 2;
      if (se.style == Series::Style::bars) fill_rect(im, all, x + 4 * s, y, x + sw - 4 * s, y + 7 * s - 1, c);
      if (se.style == Series::Style::line || se.style == Series::Style::line_points)
        draw_line(im, all, x, mid, x + sw - 1, mid, c, 2 * s);
      if (se.style == Series::Style::points || se.style == Series::Style::line_points)
        draw_disc(im, all, x + sw / 2, mid, 3 * s, c);
      draw_text(im, x + sw + ip, y, se.label, kText, s);
    }
  }

  if (!L.has_data) {
    const std::string note = "no data";
    const int w = text_width(note, s + 1);
    draw_halo_text(im, plot_mid_x - w / 2, plot_mid_y - text_height(s + 1) / 2, note, kNote, s + 1);
  }
  return im;
}

void write_chart_png(const std::string& path, const Chart& chart) {
  std::vector<std::pair<std::string, std::string>> text;
  if (!chart.title.empty()) text.emplace_back("Title", chart.title);
  text.emplace_back("Software", "snapfit");
  write_png(path, render_chart(chart), text);
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
  Extent e;
  std::size_t n = 0;
  for (double v : values)
    if (std::isfinite(v)) {
      e.add(v);
      ++n;
    }
  const std::size_t skipped = values.size() - n;
  s.label = std::to_string(n) + " values" + (skipped ? " (" + std::to_string(skipped) + " not finite)" : "");
  if (n > 0) {
    double lo = e.lo, hi = e.hi;
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

}  // namespace snapfit
