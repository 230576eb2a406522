// Field slices as figures with axes, colour bar and outline (report/slice_figure.h):
// every grid point's block has the colour map's colour at its value, the colour bar runs
// from the range's low end to its high end, the outline lands where its scene
// coordinates say, and there is text below and beside the field.
#include <algorithm>
#include <array>
#include <cmath>
#include <doctest/doctest.h>
#include <vector>

#include "report/slice_figure.h"
#include "snapfit/error.h"

using namespace snapfit;

namespace {

using Rgb = std::array<unsigned char, 3>;

Rgb pixel(const SliceImage& im, int x, int y) {
  const std::size_t p = 3 * (static_cast<std::size_t>(y) * im.width + x);
  return {im.rgb[p], im.rgb[p + 1], im.rgb[p + 2]};
}

bool dark(const Rgb& c) { return c[0] < 90 && c[1] < 90 && c[2] < 90; }

}  // namespace

TEST_CASE("slice figure: field blocks, colour bar, outline and labels where they belong") {
  GridSpec grid;
  grid.origin = Eigen::Vector3d(-5, -2.5, -2);
  grid.spacing = 0.5;
  grid.dims = Eigen::Vector3i(21, 11, 9);
  std::vector<float> f(grid.count());
  for (std::size_t i = 0; i < f.size(); ++i) f[i] = static_cast<float>(grid.point(i).x() + 0.25 * grid.point(i).z());
  const int index = 5;  // y = 0

  SliceFigureOptions options;
  options.title = "x + z/4 at y = 0";
  options.units = "mm";
  options.value_label = "f";
  const SliceFigure fig = render_slice_figure(grid, f.data(), 'y', index, ColorMap::diverging, options);
  // Automatic size: the longer side (21 points) at least 480 pixels.
  CHECK(fig.scale == 23);
  CHECK(fig.columns == 21);
  CHECK(fig.rows == 9);
  CHECK(fig.image.rgb.size() == 3u * fig.image.width * fig.image.height);
  const double limit = 5 + 0.25 * 2;  // the largest |f| in the slice
  CHECK(fig.image.value_max == doctest::Approx(limit));
  CHECK(fig.image.value_min == doctest::Approx(-limit));

  // Every block's centre has the map's colour at that grid point, and pixel_x/pixel_y put
  // the point's scene coordinates at that centre.
  for (int row = 0; row < fig.rows; ++row)
    for (int col = 0; col < fig.columns; ++col) {
      const int k = fig.rows - 1 - row;  // rows grow upward in z
      const double value = f[grid.index(col, index, k)];
      const int x = fig.left + col * fig.scale + fig.scale / 2, y = fig.top + row * fig.scale + fig.scale / 2;
      CHECK(pixel(fig.image, x, y) == map_color(ColorMap::diverging, value, -limit, limit));
      const Eigen::Vector3d p = grid.point(col, index, k);
      CHECK(fig.pixel_x(p.x()) == doctest::Approx(fig.left + (col + 0.5) * fig.scale));
      CHECK(fig.pixel_y(p.z()) == doctest::Approx(fig.top + (row + 0.5) * fig.scale));
    }

  // The colour bar: the low end at the bottom, the high end at the top, red growing upward.
  const int bx = (fig.bar_left + fig.bar_right) / 2;
  const Rgb bottom = pixel(fig.image, bx, fig.bar_bottom - 1), top = pixel(fig.image, bx, fig.bar_top);
  CHECK(bottom[2] == 255);
  CHECK(bottom[0] < 10);
  CHECK(top[0] == 255);
  CHECK(top[2] < 10);
  for (int y = fig.bar_top + 1; y < fig.bar_bottom; ++y)
    CHECK(pixel(fig.image, bx, y)[0] <= pixel(fig.image, bx, y - 1)[0]);

  // Labels: dark text pixels below the field (x ticks and label) and left of it (z).
  // They need their font; without it this says what is missing.
  const std::string font = figure_font_problem();
  REQUIRE_MESSAGE(font.empty(), font);
  int below = 0, left = 0;
  for (int y = fig.top + fig.rows * fig.scale + 8; y < fig.image.height; ++y)
    for (int x = fig.left; x < fig.left + fig.columns * fig.scale; ++x) below += dark(pixel(fig.image, x, y));
  for (int y = fig.top; y < fig.top + fig.rows * fig.scale; ++y)
    for (int x = 0; x < fig.left - 6; ++x) left += dark(pixel(fig.image, x, y));
  CHECK(below > 100);
  CHECK(left > 100);

  // An outline segment from (-2, -1) to (2, -1) in (x, z): dark along its row, the field
  // untouched away from it.
  options.outline = {OutlineSegment{Eigen::Vector2d(-2, -1), Eigen::Vector2d(2, -1)}};
  const SliceFigure lined = render_slice_figure(grid, f.data(), 'y', index, ColorMap::diverging, options);
  for (double u : {-1.5, 0.0, 1.5}) {
    const int x = static_cast<int>(lined.pixel_x(u)), y = static_cast<int>(std::round(lined.pixel_y(-1)));
    bool any = false;
    for (int dy = -1; dy <= 1; ++dy) any |= dark(pixel(lined.image, x, y + dy));
    CHECK(any);
  }
  const int fx = static_cast<int>(lined.pixel_x(0)), fy = static_cast<int>(lined.pixel_y(1.5));
  CHECK(pixel(lined.image, fx, fy) == pixel(fig.image, fx, fy));

  // NaN: magenta blocks, and a note under the colour bar (none without NaN).
  auto note_pixels = [](const SliceFigure& g) {
    int n = 0;
    for (int y = g.bar_bottom + 6; y < std::min(g.image.height, g.bar_bottom + 26); ++y)
      for (int x = g.bar_left; x < std::min(g.image.width, g.bar_left + 90); ++x) n += dark(pixel(g.image, x, y));
    return n;
  };
  CHECK(note_pixels(fig) == 0);
  std::vector<float> holes = f;
  holes[grid.index(3, index, 4)] = std::nanf("");
  const SliceFigure nan_fig = render_slice_figure(grid, holes.data(), 'y', index, ColorMap::diverging, options);
  CHECK(note_pixels(nan_fig) > 20);
  CHECK(pixel(nan_fig.image, nan_fig.left + 3 * nan_fig.scale + 1, nan_fig.top + 4 * nan_fig.scale + 1) ==
        Rgb{255, 0, 255});

  // Chosen sizes and bad input.
  options.pixels_per_point = 3;
  CHECK(render_slice_figure(grid, f.data(), 'z', 4, ColorMap::sequential, options).scale == 3);
  options.pixels_per_point = -1;
  CHECK_THROWS_AS(render_slice_figure(grid, f.data(), 'y', index, ColorMap::diverging, options), Error);
  options.pixels_per_point = 0;
  CHECK_THROWS_AS(render_slice_figure(grid, f.data(), 'y', 11, ColorMap::diverging, options), Error);
  CHECK_THROWS_AS(render_slice_figure(grid, f.data(), 'q', 0, ColorMap::diverging, options), Error);
}
