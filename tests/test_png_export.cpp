// Colour-mapped slices and PNG export (io/png_export.h), read back with libpng.
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <doctest/doctest.h>
#include <filesystem>
#include <limits>
#include <map>
#include <png.h>
#include <string>
#include <vector>

#include "io/png_export.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

using test::error_of;

using Rgb = std::array<int, 3>;
const Rgb kWhite = {255, 255, 255}, kBlue = {0, 0, 255}, kRed = {255, 0, 0}, kMagenta = {255, 0, 255};
const Rgb kViridisLow = {68, 1, 84}, kViridisHigh = {253, 231, 37};

Rgb pixel(const SliceImage& im, int x, int y) {
  const std::size_t p = 3 * (static_cast<std::size_t>(y) * im.width + x);
  return {im.rgb[p], im.rgb[p + 1], im.rgb[p + 2]};
}

// Grid points at x = -2..2, y = 0..3, z = 0..2 (spacing 1).
GridSpec small_grid() {
  GridSpec g;
  g.origin = Eigen::Vector3d(-2.0, 0.0, 0.0);
  g.spacing = 1.0;
  g.dims = Eigen::Vector3i(5, 4, 3);
  return g;
}

// value = f(x, y, z) at every grid point.
template <class F>
std::vector<float> sample(const GridSpec& g, F f) {
  std::vector<float> v(g.count());
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        const Eigen::Vector3d p = g.point(i, j, k);
        v[g.index(i, j, k)] = static_cast<float>(f(p.x(), p.y(), p.z()));
      }
  return v;
}

// A PNG read back with libpng's own reader.
struct ReadPng {
  png_uint_32 width = 0, height = 0;
  int bit_depth = 0, color_type = 0;
  std::vector<unsigned char> rgb;
  std::map<std::string, std::string> text;  // tEXt chunks only
  int other_text = 0;                       // zTXt / iTXt chunks
};

// All output goes through `out` (not a local of this frame), so longjmp is harmless.
bool read_png(std::FILE* f, ReadPng* out) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (png == nullptr) return false;
  png_infop info = png_create_info_struct(png);
  if (info == nullptr || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, f);
  png_read_info(png, info);
  out->width = png_get_image_width(png, info);
  out->height = png_get_image_height(png, info);
  out->bit_depth = png_get_bit_depth(png, info);
  out->color_type = png_get_color_type(png, info);
  if (out->color_type == PNG_COLOR_TYPE_RGB && out->bit_depth == 8) {
    out->rgb.resize(3 * static_cast<std::size_t>(out->width) * out->height);
    for (png_uint_32 y = 0; y < out->height; ++y) png_read_row(png, out->rgb.data() + 3 * out->width * y, nullptr);
  }
  png_read_end(png, info);
  png_textp text = nullptr;
  const int n = png_get_text(png, info, &text, nullptr);
  for (int t = 0; t < n; ++t) {
    if (text[t].compression == PNG_TEXT_COMPRESSION_NONE)
      out->text[text[t].key] = std::string(text[t].text, text[t].text_length);
    else
      ++out->other_text;
  }
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

TEST_CASE("png slice: diverging colours of value = x, limit from the slice") {
  const GridSpec g = small_grid();
  const std::vector<float> v = sample(g, [](double x, double, double) { return x; });
  const SliceImage im = render_slice(g, v.data(), 'z', 1, ColorMap::diverging);
  REQUIRE(im.width == 5);
  REQUIRE(im.height == 4);
  REQUIRE(im.rgb.size() == 5u * 4u * 3u);
  CHECK(im.value_min == -2.0);
  CHECK(im.value_max == 2.0);
  for (int y = 0; y < 4; ++y) {
    CHECK(pixel(im, 0, y) == kBlue);               // x = -2 = -limit
    CHECK(pixel(im, 2, y) == kWhite);              // x = 0
    CHECK(pixel(im, 4, y) == kRed);                // x = +2 = +limit
    CHECK(pixel(im, 1, y) == Rgb{128, 128, 255});  // halfway to blue (127.5 rounds up)
    CHECK(pixel(im, 3, y) == Rgb{255, 128, 128});
  }
}

TEST_CASE("png slice: a given symmetric limit, clamping and infinities") {
  const GridSpec g = small_grid();
  std::vector<float> v = sample(g, [](double x, double, double) { return 0.5 * x; });  // -1..1
  v[g.index(2, 0, 0)] = std::numeric_limits<float>::infinity();
  const SliceImage im = render_slice(g, v.data(), 'z', 0, ColorMap::diverging, 4.0);
  CHECK(im.value_min == -4.0);
  CHECK(im.value_max == 4.0);
  CHECK(pixel(im, 0, 0) == Rgb{191, 191, 255});  // -1 of 4: a quarter of the way to blue
  CHECK(pixel(im, 2, 3) == kRed);                // +inf at (i=2, j=0), the bottom row
  const SliceImage tight = render_slice(g, v.data(), 'z', 0, ColorMap::diverging, 0.5);
  CHECK(pixel(tight, 0, 0) == kBlue);  // -1 clamped to -0.5
  CHECK(pixel(tight, 4, 0) == kRed);
}

TEST_CASE("png slice: orientation, top row is the largest index, for every axis") {
  const GridSpec g = small_grid();  // 5 x 4 x 3
  // A field that is positive only at one marked point per axis pair.
  const std::vector<float> v = sample(g, [](double x, double y, double z) {
    return (x == 2.0 && y == 3.0) || (x == 2.0 && z == 2.0) || (y == 3.0 && z == 2.0) ? 1.0 : -1.0;
  });
  // z slice: column = i, row 0 = j max. The point (i=4, j=3) is the top right.
  const SliceImage z = render_slice(g, v.data(), 'z', 0, ColorMap::diverging);
  REQUIRE(z.width == 5);
  REQUIRE(z.height == 4);
  CHECK(pixel(z, 4, 0) == kRed);
  CHECK(pixel(z, 4, 3) == kBlue);
  CHECK(pixel(z, 0, 0) == kBlue);
  // y slice at j=0: column = i, row 0 = k max. (i=4, k=2) is the top right.
  const SliceImage y = render_slice(g, v.data(), 'y', 0, ColorMap::diverging);
  REQUIRE(y.width == 5);
  REQUIRE(y.height == 3);
  CHECK(pixel(y, 4, 0) == kRed);
  CHECK(pixel(y, 4, 2) == kBlue);
  // x slice at i=0: column = j, row 0 = k max. (j=3, k=2) is the top right.
  const SliceImage x = render_slice(g, v.data(), 'x', 0, ColorMap::diverging);
  REQUIRE(x.width == 4);
  REQUIRE(x.height == 3);
  CHECK(pixel(x, 3, 0) == kRed);
  CHECK(pixel(x, 3, 2) == kBlue);
  CHECK(pixel(x, 0, 0) == kBlue);
}

TEST_CASE("png slice: sequential map over [min, max] is ordered dark to bright") {
  GridSpec g;
  g.dims = Eigen::Vector3i(101, 1, 1);
  g.origin = Eigen::Vector3d(10.0, 0.0, 0.0);
  const std::vector<float> v = sample(g, [](double x, double, double) { return x; });  // 10..110
  const SliceImage im = render_slice(g, v.data(), 'z', 0, ColorMap::sequential);
  CHECK(im.value_min == 10.0);
  CHECK(im.value_max == 110.0);
  CHECK(pixel(im, 0, 0) == kViridisLow);
  CHECK(pixel(im, 100, 0) == kViridisHigh);
  CHECK(pixel(im, 50, 0) == Rgb{33, 145, 140});  // the control point at 50%
  // Relative luminance grows along the ramp (perceptual order).
  double last = -1.0;
  int drops = 0;
  for (int x = 0; x <= 100; ++x) {
    const Rgb c = pixel(im, x, 0);
    const double lum = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    drops += lum < last;
    last = lum;
  }
  CHECK(drops == 0);
  // A constant slice gets the low end; an all-zero diverging slice is white.
  const std::vector<float> flat(g.count(), 3.0f), zero(g.count(), 0.0f);
  const SliceImage c = render_slice(g, flat.data(), 'z', 0, ColorMap::sequential);
  CHECK(pixel(c, 7, 0) == kViridisLow);
  CHECK(c.value_min == 3.0);
  CHECK(c.value_max == 3.0);
  CHECK(pixel(render_slice(g, zero.data(), 'z', 0, ColorMap::diverging), 7, 0) == kWhite);
}

TEST_CASE("png slice: NaN is magenta and is left out of the range") {
  const GridSpec g = small_grid();
  std::vector<float> v = sample(g, [](double x, double, double) { return x; });
  v[g.index(1, 3, 2)] = std::numeric_limits<float>::quiet_NaN();
  v[g.index(0, 0, 2)] = std::numeric_limits<float>::quiet_NaN();  // the -2 end
  for (ColorMap map : {ColorMap::diverging, ColorMap::sequential}) {
    const SliceImage im = render_slice(g, v.data(), 'z', 2, map);
    CHECK(pixel(im, 1, 0) == kMagenta);  // j = 3 is the top row
    CHECK(pixel(im, 0, 3) == kMagenta);
    CHECK(pixel(im, 0, 0) != kMagenta);
    if (map == ColorMap::sequential) CHECK(im.value_min == -2.0);  // other rows still hold -2
  }
  std::vector<float> all_nan(g.count(), std::numeric_limits<float>::quiet_NaN());
  const SliceImage none = render_slice(g, all_nan.data(), 'y', 1, ColorMap::sequential);
  CHECK(none.value_min == 0.0);
  CHECK(none.value_max == 0.0);
  CHECK(pixel(none, 2, 1) == kMagenta);
}

TEST_CASE("png slice: each grid point is a scale x scale block") {
  const GridSpec g = small_grid();
  const std::vector<float> v = sample(g, [](double x, double y, double) { return x + 10 * y; });
  const SliceImage one = render_slice(g, v.data(), 'z', 0, ColorMap::sequential);
  const SliceImage big = render_slice(g, v.data(), 'z', 0, ColorMap::sequential, std::nullopt, 3);
  REQUIRE(big.width == 15);
  REQUIRE(big.height == 12);
  int mismatches = 0;
  for (int y = 0; y < big.height; ++y)
    for (int x = 0; x < big.width; ++x) mismatches += pixel(big, x, y) != pixel(one, x / 3, y / 3);
  CHECK(mismatches == 0);
}

TEST_CASE("png slice: bad axis, index, limit and scale throw") {
  const GridSpec g = small_grid();
  const std::vector<float> v(g.count(), 1.0f);
  CHECK(test::error_of([&] { render_slice(g, v.data(), 'w', 0, ColorMap::diverging); }).find("axis must be") !=
        std::string::npos);
  CHECK(test::error_of([&] { render_slice(g, v.data(), 'z', 3, ColorMap::diverging); }).find("outside the grid") !=
        std::string::npos);
  CHECK(test::error_of([&] { render_slice(g, v.data(), 'x', -1, ColorMap::diverging); }).find("outside the grid") !=
        std::string::npos);
  CHECK(test::error_of([&] { render_slice(g, v.data(), 'x', 5, ColorMap::diverging); }).find("outside the grid") !=
        std::string::npos);
  CHECK_NOTHROW(render_slice(g, v.data(), 'x', 4, ColorMap::diverging));
  CHECK(test::error_of([&] { render_slice(g, nullptr, 'z', 0, ColorMap::diverging); }).find("null") !=
        std::string::npos);
  CHECK(test::error_of([&] { render_slice(g, v.data(), 'z', 0, ColorMap::diverging, 0.0); }).find("limit") !=
        std::string::npos);
  CHECK(test::error_of([&] {
          render_slice(g, v.data(), 'z', 0, ColorMap::diverging, std::nullopt, 0);
        }).find("scale") != std::string::npos);
  GridSpec empty = g;
  empty.dims.y() = 0;
  CHECK(test::error_of([&] { render_slice(empty, v.data(), 'z', 0, ColorMap::diverging); }).find("empty grid") !=
        std::string::npos);
}

TEST_CASE("png write: read back with libpng, pixels and tEXt chunks") {
  test::TempDir dir;
  const GridSpec g = small_grid();
  std::vector<float> v = sample(g, [](double x, double y, double z) { return x * y - z; });
  v[3] = std::numeric_limits<float>::quiet_NaN();
  const SliceImage im = render_slice(g, v.data(), 'y', 2, ColorMap::diverging, std::nullopt, 2);
  const std::string path = dir.file("slice.png");
  const std::vector<std::pair<std::string, std::string>> text = {
      {"Title", "energy, y slice 2"}, {"value_min", "-6"}, {"value_max", "6"}, {"Comment", ""}};
  write_png(path, im, text);
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir.path)) files += e.is_regular_file();
  CHECK(files == 1);

  ReadPng r;
  std::FILE* f = std::fopen(path.c_str(), "rb");
  REQUIRE(f != nullptr);
  const bool ok = read_png(f, &r);
  std::fclose(f);
  REQUIRE(ok);
  CHECK(r.width == static_cast<png_uint_32>(im.width));
  CHECK(r.height == static_cast<png_uint_32>(im.height));
  CHECK(r.bit_depth == 8);
  CHECK(r.color_type == PNG_COLOR_TYPE_RGB);
  CHECK(r.rgb == im.rgb);
  CHECK(r.other_text == 0);
  CHECK(r.text.size() == text.size());
  for (const auto& [key, value] : text) CHECK(r.text[key] == value);

  // The same PNG in memory, byte for byte.
  const std::vector<char> file = test::read_bytes(path);
  const std::vector<unsigned char> memory = png_bytes(im, text);
  CHECK(std::vector<unsigned char>(file.begin(), file.end()) == memory);
  CHECK_THROWS_AS(png_bytes(SliceImage{}), Error);
}

TEST_CASE("png write: malformed images, bad keywords and unwritable paths throw naming the path") {
  test::TempDir dir;
  const std::string path = dir.file("bad.png");
  SliceImage im;
  im.width = 2;
  im.height = 2;
  im.rgb.assign(11, 0);
  std::string m = test::error_of([&] { write_png(path, im); });
  CHECK(m.find(path) != std::string::npos);
  CHECK(m.find("bytes of RGB") != std::string::npos);
  im.rgb.assign(12, 0);
  CHECK(test::error_of([&] { write_png(path, im, {{"", "x"}}); }).find("keyword") != std::string::npos);
  CHECK(test::error_of([&] {
          write_png(path, im, {{std::string(80, 'k'), "x"}});
        }).find("keyword") != std::string::npos);
  CHECK(test::error_of([&] { write_png(path, im, {{" lead", "x"}}); }).find("keyword") != std::string::npos);
  CHECK(test::error_of([&] { write_png(path, im, {{"k", std::string("a\0b", 3)}}); }).find("NUL") != std::string::npos);
  SliceImage empty;
  CHECK(test::error_of([&] { write_png(path, empty); }).find("image size") != std::string::npos);
  const std::string nowhere = dir.file("missing/x.png");
  m = test::error_of([&] { write_png(nowhere, im); });
  CHECK(m.find(nowhere) != std::string::npos);
  CHECK(std::filesystem::is_empty(dir.path));
}

TEST_CASE("png slice_index_for: nearest index inside, errors outside") {
  GridSpec g;
  g.origin = Eigen::Vector3d(-1.0, 2.0, 0.0);
  g.spacing = 0.5;
  g.dims = Eigen::Vector3i(5, 3, 21);  // x in [-1, 1], y in [2, 3], z in [0, 10]
  CHECK(slice_index_for(g, 'x', -1.0) == 0);
  CHECK(slice_index_for(g, 'x', 1.0) == 4);
  CHECK(slice_index_for(g, 'x', 0.2) == 2);
  CHECK(slice_index_for(g, 'x', 0.3) == 3);
  CHECK(slice_index_for(g, 'y', 2.74) == 1);
  CHECK(slice_index_for(g, 'z', 10.0) == 20);
  CHECK(slice_index_for(g, 'z', 0.1 + 0.2) == 1);
  CHECK(test::error_of([&] { slice_index_for(g, 'z', 12.5); }) ==
        "z=12.5 is outside the grid, which spans z in [0, 10]");
  CHECK(test::error_of([&] { slice_index_for(g, 'x', -1.01); }) ==
        "x=-1.01 is outside the grid, which spans x in [-1, 1]");
  CHECK(test::error_of([&] { slice_index_for(g, 'y', std::nan("")); }).find("outside the grid") != std::string::npos);
  CHECK(test::error_of([&] { slice_index_for(g, 'q', 0.0); }).find("axis must be") != std::string::npos);
}
