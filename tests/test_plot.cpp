// Charts to PNG (report/plot.h) and the bitmap font (report/bitmap_font.h).
#include <array>
#include <cmath>
#include <cstring>
#include <doctest/doctest.h>
#include <limits>
#include <png.h>
#include <string>
#include <vector>

#include "report/bitmap_font.h"
#include "report/plot.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

using test::error_of;

using Rgb = std::array<int, 3>;
const Rgb kWhite = {255, 255, 255};

Rgb pixel(const SliceImage& im, int x, int y) {
  const std::size_t p = 3 * (static_cast<std::size_t>(y) * im.width + x);
  return {im.rgb[p], im.rgb[p + 1], im.rgb[p + 2]};
}

int px(double v) { return static_cast<int>(std::lround(v)); }

bool near(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-9 * std::max(1.0, std::abs(b[i]))) return false;
  return true;
}

// A chart with both axes fixed to [0, 10] and one series.
Chart fixed_chart(Series s) {
  Chart c;
  c.x_min = c.y_min = 0;
  c.x_max = c.y_max = 10;
  c.series.push_back(std::move(s));
  return c;
}

Series make_series(std::vector<double> x, std::vector<double> y, Series::Style style,
                   std::array<unsigned char, 3> color, std::string label = "") {
  Series s;
  s.x = std::move(x);
  s.y = std::move(y);
  s.style = style;
  s.color = color;
  s.label = std::move(label);
  return s;
}

}  // namespace

TEST_CASE("plot: linear ticks use 1-2-5 steps inside the range") {
  // Decision: ticks stay inside [lo, hi]; [0, 9.3] gives 0, 2, 4, 6, 8 (not up to 10).
  AxisTicks t = linear_ticks(0, 9.3, 6);
  CHECK(near(t.major, {0, 2, 4, 6, 8}));
  CHECK(t.step == 2);
  CHECK(t.minor.empty());
  CHECK(near(linear_ticks(0, 9.3, 10).major, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  CHECK(near(linear_ticks(0, 1, 5).major, {0, 0.5, 1}));
  t = linear_ticks(-0.013, 0.042, 6);
  CHECK(near(t.major, {-0.01, 0, 0.01, 0.02, 0.03, 0.04}));
  CHECK(t.major[1] == 0.0);  // exactly zero, so its label is "0"
  CHECK(near(linear_ticks(1200, 5100, 5).major, {2000, 3000, 4000, 5000}));

  CHECK(tick_label(0.1 * 3, 0.1) == "0.3");
  CHECK(tick_label(2, 2) == "2");
  CHECK(tick_label(-0.5, 0.5) == "-0.5");
  CHECK(tick_label(0.75, 0.25) == "0.75");
  CHECK(tick_label(1e-12, 0.1) == "0");
  CHECK(tick_label(2e6, 1e6) == "2e6");
  CHECK(tick_label(1.5e-5, 5e-6) == "1.5e-5");
  CHECK(tick_label(0.001, 0) == "0.001");  // log decades label themselves
  CHECK(tick_label(100000, 0) == "100000");
  CHECK(tick_label(1e-7, 0) == "1e-7");
  CHECK(tick_label(1e9, 0) == "1e9");
}

TEST_CASE("plot: log ticks are decades with minor ticks at 2..9") {
  AxisTicks t = log_ticks(3, 4000, 6);
  CHECK(near(t.major, {10, 100, 1000}));
  CHECK(t.step == 0);
  REQUIRE(t.minor.size() == 7 + 8 + 8 + 3);  // 3..9, 20..90, 200..900, 2000..4000
  CHECK(t.minor.front() == doctest::Approx(3));
  CHECK(t.minor[7] == doctest::Approx(20));
  CHECK(t.minor.back() == doctest::Approx(4000));

  // Thirteen decades: every third labelled, the others minor.
  t = log_ticks(1e-6, 1e6, 6);
  CHECK(near(t.major, {1e-6, 1e-3, 1, 1e3, 1e6}));
  CHECK(t.minor.size() == 8);

  // No decade inside: 1-2-5 labels.
  t = log_ticks(1.5, 8, 6);
  CHECK(near(t.major, {2, 5}));
  CHECK(near(t.minor, {3, 4, 6, 7, 8}));

  // Too narrow even for that: linear ticks.
  t = log_ticks(3.1, 3.4, 6);
  CHECK(near(t.major, {3.1, 3.2, 3.3, 3.4}));
  CHECK(t.step == doctest::Approx(0.1));
}

TEST_CASE("plot: data coordinates land on the expected pixels") {
  const std::array<unsigned char, 3> red = {200, 30, 30};
  Chart c = fixed_chart(make_series({2, 7}, {3, 8}, Series::Style::points, red));
  const ChartLayout L = chart_layout(c);
  CHECK(L.left > 0);
  CHECK(L.right < c.width - 1);
  CHECK(L.top > 0);
  CHECK(L.bottom < c.height - 1);
  CHECK(pixel_x(L, 0) == doctest::Approx(L.left));
  CHECK(pixel_x(L, 10) == doctest::Approx(L.right));
  CHECK(pixel_y(L, 0) == doctest::Approx(L.bottom));
  CHECK(pixel_y(L, 10) == doctest::Approx(L.top));
  CHECK(pixel_x(L, 2) == doctest::Approx(L.left + 0.2 * (L.right - L.left)));
  CHECK(pixel_y(L, 3) == doctest::Approx(L.bottom - 0.3 * (L.bottom - L.top)));

  const SliceImage im = render_chart(c);
  REQUIRE(im.width == 800);
  REQUIRE(im.height == 500);
  const Rgb want = {200, 30, 30};
  CHECK(pixel(im, px(pixel_x(L, 2)), px(pixel_y(L, 3))) == want);
  CHECK(pixel(im, px(pixel_x(L, 7)), px(pixel_y(L, 8))) == want);
  CHECK(pixel(im, px(pixel_x(L, 2)) + 2, px(pixel_y(L, 3)) + 2) == want);  // a disc, not one pixel
  CHECK(pixel(im, px(pixel_x(L, 5.1)), px(pixel_y(L, 1.1))) == kWhite);    // between grid lines, no data
  CHECK(pixel(im, 0, 0) == kWhite);

  // Log axis: one decade of three spans a third of the width.
  c.log_x = true;
  c.x_min = 1;
  c.x_max = 1000;
  const ChartLayout G = chart_layout(c);
  CHECK(pixel_x(G, 10) == doctest::Approx(G.left + (G.right - G.left) / 3.0));
  CHECK(std::isnan(pixel_x(G, 0)));
  CHECK(std::isnan(pixel_x(G, -5)));
  CHECK(std::isnan(pixel_y(G, std::nan(""))));
}

TEST_CASE("plot: a reference line is dashed along its row") {
  Chart c = fixed_chart(make_series({0, 10}, {1, 1}, Series::Style::line, {30, 30, 200}));
  c.hlines.push_back({8.0, ""});
  const ChartLayout L = chart_layout(c);
  const SliceImage im = render_chart(c);
  auto dark_grey = [&](int x, int y) {
    const Rgb p = pixel(im, x, y);
    return p[0] == p[1] && p[1] == p[2] && p[0] < 160;
  };
  const int row = px(pixel_y(L, 8.0));
  int on = 0;
  for (int x = L.left; x <= L.right; ++x) on += dark_grey(x, row);
  const int width = L.right - L.left + 1;
  CHECK(on > width / 2);  // dashes...
  CHECK(on < width);      // ...with gaps
  for (int x = L.left; x <= L.right; ++x) {
    CHECK_FALSE(dark_grey(x, row - 3));
    CHECK_FALSE(dark_grey(x, row + 4));
  }
}

TEST_CASE("plot: lines are clipped to the plot area") {
  const std::array<unsigned char, 3> green = {0, 170, 0};
  const double nan = std::nan("");
  Chart c = fixed_chart(
      make_series({5, 1e6, 5, -1e300, nan, 5, 5}, {5, 1e6, -1e9, 5, 5, 5, 1e12}, Series::Style::line_points, green));
  const ChartLayout L = chart_layout(c);
  const SliceImage im = render_chart(c);
  const Rgb want = {0, 170, 0};
  int inside = 0;
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const bool in = x >= L.left && x <= L.right && y >= L.top && y <= L.bottom;
      if (in)
        inside += pixel(im, x, y) == want;
      else if (pixel(im, x, y) == want)
        FAIL("series pixel outside the plot area at " << x << ", " << y);
    }
  CHECK(inside > 200);
  // The margins right of the frame and above the top tick label stay white.
  for (int y = L.top; y <= L.bottom; ++y)
    for (int x = L.right + 2; x < im.width; ++x) REQUIRE(pixel(im, x, y) == kWhite);
  for (int y = 0; y < L.top - 6; ++y)
    for (int x = 0; x < im.width; ++x) REQUIRE(pixel(im, x, y) == kWhite);
}

TEST_CASE("plot: the font draws known glyph bitmaps") {
  const std::array<unsigned char, kGlyphRows> one = {0b00100, 0b01100, 0b00100, 0b00100,
                                                     0b00100, 0b00100, 0b01110, 0b00000};
  CHECK(glyph_rows('1') == one);
  CHECK(glyph_rows('\x7f') == glyph_rows('?'));
  CHECK(glyph_rows('\n') == glyph_rows('?'));

  SliceImage im;
  im.width = 20;
  im.height = 12;
  im.rgb.assign(3 * 20 * 12, 255);
  draw_text(im, 2, 1, "1", {0, 0, 0}, 1);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) {
      const int col = x - 2, row = y - 1;
      const bool ink = col >= 0 && col < 5 && row >= 0 && row < 8 && (one[row] >> (4 - col) & 1);
      CHECK(pixel(im, x, y) == (ink ? Rgb{0, 0, 0} : kWhite));
    }

  // Scale 2: each font pixel a 2 x 2 block; vertical text reads bottom to top.
  im.rgb.assign(im.rgb.size(), 255);
  draw_text(im, 0, 0, "1", {9, 9, 9}, 2);
  for (int y = 0; y < 12; ++y)
    for (int x = 0; x < 10; ++x) CHECK((pixel(im, x, y)[0] == 9) == bool(one[y / 2] >> (4 - x / 2) & 1));
  im.rgb.assign(im.rgb.size(), 255);
  draw_text(im, 0, 0, "1", {9, 9, 9}, 1, true);
  for (int u = 0; u < 5; ++u)
    for (int v = 0; v < 8; ++v) CHECK((pixel(im, v, 4 - u)[0] == 9) == bool(one[v] >> (4 - u) & 1));

  CHECK(text_width("", 1) == 0);
  CHECK(text_width("1", 1) == 5);
  CHECK(text_width("11", 1) == 11);
  CHECK(text_width("1", 2) == 10);
  CHECK(text_width("i", 1) == 3);  // proportional letters, fixed-width digits
  CHECK(text_width("1 1", 1) == 14);

  // Every printable character but space has ink, and no two look alike.
  for (int a = 33; a <= 126; ++a) {
    unsigned any = 0;
    for (unsigned char r : glyph_rows(static_cast<char>(a))) any |= r;
    CHECK_MESSAGE(any != 0, "glyph " << char(a));
    for (int b = a + 1; b <= 126; ++b)
      CHECK_MESSAGE(glyph_rows(static_cast<char>(a)) != glyph_rows(static_cast<char>(b)),
                    "glyphs " << char(a) << " and " << char(b));
  }
}

TEST_CASE("plot: log axes skip non-positive values") {
  const std::array<unsigned char, 3> blue = {20, 60, 220};
  Chart c;
  c.log_y = true;
  c.series.push_back(make_series({1, 2, 3, 4, 5}, {-1, 0, 1, 10, 100}, Series::Style::points, blue));
  ChartLayout L = chart_layout(c);
  CHECK(L.has_data);
  CHECK(L.y_lo > 0.5);
  CHECK(L.y_lo < 1);
  CHECK(L.y_hi > 100);
  CHECK(L.x_lo > 2);  // x of the skipped points does not count either
  const SliceImage im = render_chart(c);
  CHECK(pixel(im, px(pixel_x(L, 3)), px(pixel_y(L, 1))) == Rgb{20, 60, 220});

  // Only non-positive values: axes and the note, no failure.
  c.series[0].y = {-1, 0, -3, 0, -5};
  L = chart_layout(c);
  CHECK_FALSE(L.has_data);
  CHECK(L.y_lo > 0);
  CHECK_NOTHROW(render_chart(c));

  // Log x; non-finite values on a linear axis.
  Chart d;
  d.log_x = true;
  d.series.push_back(make_series({-1, 0, 10, 1000, std::nan("")}, {1, 2, 3, 4, 5}, Series::Style::line, blue));
  d.series.push_back(make_series({20, 30}, {HUGE_VAL, -HUGE_VAL}, Series::Style::line, blue));
  L = chart_layout(d);
  CHECK(L.x_lo > 5);
  CHECK(L.x_hi < 2000);
  CHECK(L.y_lo > 2);
  CHECK(L.y_hi < 5);
  CHECK_NOTHROW(render_chart(d));

  // Values near the double limit still give a finite range.
  Chart e;
  e.series.push_back(make_series({-1e308, 1e308}, {1e308, -1e308}, Series::Style::line_points, blue));
  L = chart_layout(e);
  CHECK(std::isfinite(L.x_hi - L.x_lo));
  CHECK(L.x_ticks.major.size() >= 2);
  CHECK_NOTHROW(render_chart(e));
}

TEST_CASE("plot: empty charts draw axes and a no-data note") {
  Chart c;
  c.title = "nothing";
  c.series.push_back(Series{"empty", {}, {}, Series::Style::line, {0, 0, 0}});
  const ChartLayout L = chart_layout(c);
  CHECK_FALSE(L.has_data);
  const SliceImage im = render_chart(c);
  // The frame on the left of the plot area.
  CHECK(pixel(im, L.left - 1, (L.top + L.bottom) / 2) != kWhite);
  // Grey note text somewhere around the middle.
  int grey = 0;
  for (int y = (L.top + L.bottom) / 2 - 10; y <= (L.top + L.bottom) / 2 + 10; ++y)
    for (int x = (L.left + L.right) / 2 - 40; x <= (L.left + L.right) / 2 + 40; ++x)
      grey += pixel(im, x, y) == Rgb{150, 150, 150};
  CHECK(grey > 20);
  CHECK_NOTHROW(render_chart(Chart{}));
}

TEST_CASE("plot: histogram_chart bins finite values into bars") {
  std::vector<double> values;
  for (int i = 0; i < 100; ++i) values.push_back(i);
  values.push_back(std::nan(""));
  Chart c = histogram_chart("h", "value", values, 10, false);
  REQUIRE(c.series.size() == 1);
  const Series& s = c.series[0];
  CHECK(s.style == Series::Style::bars);
  CHECK(s.label == "100 values (1 not finite)");
  CHECK(c.y_label == "count");
  REQUIRE(s.x.size() == 10);
  CHECK(s.x[0] == doctest::Approx(4.95));
  CHECK(s.x[9] == doctest::Approx(94.05));
  CHECK(near(s.y, std::vector<double>(10, 10.0)));

  // Bars start at 0 with no margin below and fill their bins.
  const ChartLayout L = chart_layout(c);
  CHECK(L.y_lo == 0);
  const SliceImage im = render_chart(c);
  const Rgb first = {31, 119, 180};  // the palette's first colour
  CHECK(pixel(im, px(pixel_x(L, s.x[3])), px(pixel_y(L, 5))) == first);
  CHECK(pixel(im, px(pixel_x(L, s.x[3] + 4)), px(pixel_y(L, 5))) == first);

  // Log y: empty bins are left out, the others keep their width.
  Chart g = histogram_chart("", "v", {1, 1, 1, 9, 10}, 10, true);
  const ChartLayout G = chart_layout(g);
  const SliceImage gi = render_chart(g);
  CHECK(pixel(gi, px(pixel_x(G, g.series[0].x[0] + 0.4)), G.bottom - 2) == first);
  CHECK(pixel(gi, px(pixel_x(G, 5)), G.bottom - 2) != first);

  CHECK_FALSE(chart_layout(histogram_chart("", "", {}, 5)).has_data);
  CHECK_NOTHROW(render_chart(histogram_chart("", "", {3, 3, 3}, 5)));
  CHECK(error_of([] { histogram_chart("h", "", {1}, 0); }).find("bins") != std::string::npos);
}

TEST_CASE("plot: write_chart_png round trip") {
  test::TempDir dir;
  Chart c;
  c.title = "round trip";
  c.width = 320;
  c.height = 200;
  c.series.push_back(make_series({0, 1, 2}, {0, 1, 4}, Series::Style::line_points, {0, 0, 0}, "y = x^2"));
  const std::string path = dir.file("chart.png");
  write_chart_png(path, c);

  png_image img;
  std::memset(&img, 0, sizeof img);
  img.version = PNG_IMAGE_VERSION;
  REQUIRE(png_image_begin_read_from_file(&img, path.c_str()));
  img.format = PNG_FORMAT_RGB;
  std::vector<unsigned char> rgb(PNG_IMAGE_SIZE(img));
  REQUIRE(png_image_finish_read(&img, nullptr, rgb.data(), 0, nullptr));
  CHECK(img.width == 320);
  CHECK(img.height == 200);
  const SliceImage want = render_chart(c);
  CHECK(rgb == want.rgb);
  const ChartLayout L = chart_layout(c);
  SliceImage got = want;
  got.rgb = rgb;
  CHECK(pixel(got, 0, 0) == kWhite);
  CHECK(pixel(got, px(pixel_x(L, 1)), px(pixel_y(L, 1))) == Rgb{31, 119, 180});
  CHECK(pixel(got, L.left - 1, L.bottom) != kWhite);  // frame

  // A failed write leaves nothing behind.
  CHECK(error_of([&] { write_chart_png(dir.file("missing/chart.png"), c); }).find("missing") != std::string::npos);
}

TEST_CASE("plot: invalid charts throw snapfit::Error") {
  Chart c;
  c.title = "bad";
  c.width = 99;
  CHECK(error_of([&] { render_chart(c); }) == "chart 'bad': size 99 x 500 is outside 100..8000 pixels per side");
  c.width = 8001;
  CHECK_THROWS_AS(render_chart(c), Error);
  c.width = 800;
  c.height = 50;
  CHECK_THROWS_AS(render_chart(c), Error);
  c.height = 500;
  CHECK_NOTHROW(render_chart(c));

  c.series.push_back(make_series({1, 2, 3}, {1, 2}, Series::Style::line, {0, 0, 0}, "short"));
  CHECK(error_of([&] { render_chart(c); }) == "chart 'bad': series 0 'short' has 3 x values but 2 y values");
  CHECK_THROWS_AS(write_chart_png("/nonexistent/x.png", c), Error);
  c.series.clear();

  c.text_scale = 9;
  CHECK(error_of([&] { chart_layout(c); }).find("text scale") != std::string::npos);
  c.text_scale = 0;
  c.x_min = 5;
  c.x_max = 5;
  CHECK(error_of([&] { render_chart(c); }).find("minimum must be below the maximum") != std::string::npos);
  c.x_min = 0;
  c.x_max = HUGE_VAL;
  CHECK(error_of([&] { render_chart(c); }).find("not finite") != std::string::npos);
  c.x_max = 10;
  c.log_x = true;
  CHECK(error_of([&] { render_chart(c); }).find("logarithmic") != std::string::npos);
}
