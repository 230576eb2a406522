#pragma once
// 2D slices of grid fields as colour-mapped PNG images (RGB 8-bit), as `snapfit fields
// --png`, `snapfit map --png` and the run report draw them.
//
// Slice orientation: the image's horizontal axis is the lower of the two remaining grid
// axes, growing to the right; the vertical one is the higher, growing upward (row 0 of
// the image is the top, the largest index):
//   axis 'z' (k = index): column = i, row = ny-1-j   (x right, y up; width nx, height ny)
//   axis 'y' (j = index): column = i, row = nz-1-k   (x right, z up; width nx, height nz)
//   axis 'x' (i = index): column = j, row = nz-1-k   (y right, z up; width ny, height nz)
// Each grid point becomes a scale x scale block of pixels.
#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "snapfit/grid.h"

namespace snapfit {

enum class ColorMap {
  // Signed fields: blue (0,0,255) at -limit, white at 0, red (255,0,0) at +limit,
  // linear in between, clamped beyond.
  diverging,
  // Magnitudes: viridis (11 control points at every 10%, linear in between), dark
  // purple at the slice minimum to yellow at the maximum; lightness grows monotonically.
  sequential,
};

struct SliceImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // row-major from the top row, 3 bytes per pixel
  // The values at the two ends of the colour map, for a legend: diverging
  // [-limit, +limit], sequential [slice min, slice max]. Only finite values count;
  // a slice with none gives [0, 0].
  double value_min = 0, value_max = 0;
};

// Renders the slice at `index` along `axis` of `values` (grid.count() floats, grid
// order). Diverging uses symmetric_limit, or else the largest |value| in the slice.
// NaN is drawn magenta (255,0,255); +-inf is clamped to the map's ends. A constant
// slice is drawn with the map's low end (sequential) or white (diverging, all zero).
// Throws snapfit::Error for an empty grid, null values, an axis other than 'x', 'y',
// 'z', an index outside the grid, a non-positive or non-finite symmetric_limit, and a
// scale below 1 or that makes a side longer than 1,000,000 pixels.
SliceImage render_slice(const GridSpec& grid, const float* values, char axis, int index, ColorMap map,
                        std::optional<double> symmetric_limit = std::nullopt, int scale = 1);

// The colour `map` gives `value` on a slice whose colour range is [value_min, value_max]
// (as render_slice reports it: diverging [-limit, +limit], sequential [min, max]).
std::array<unsigned char, 3> map_color(ColorMap map, double value, double value_min, double value_max);

// Writes `image` as an 8-bit RGB PNG with one tEXt chunk per (keyword, text) pair
// (keywords 1-79 Latin-1 characters, e.g. "Title", "Comment", "value_min"), through
// "<path>.tmp.<pid>" renamed onto `path`. Throws snapfit::Error naming `path` for a
// malformed image or keyword and for I/O failures; no file is left behind then.
void write_png(const std::string& path, const SliceImage& image,
               const std::vector<std::pair<std::string, std::string>>& text = {});

// The same PNG as write_png, in memory (e.g. to inline in a page). Throws snapfit::Error
// for a malformed image or keyword.
std::vector<unsigned char> png_bytes(const SliceImage& image,
                                     const std::vector<std::pair<std::string, std::string>>& text = {});

}  // namespace snapfit
