#pragma once
// A field slice as a figure that explains itself (drawn with cairo): the colour-mapped
// slice (include/snapfit/slice_image.h render_slice, one block of pixels a grid point), axes in scene
// units with ticks, the part's outline in that plane (mesh_slice_outline) drawn over it,
// a colour bar with its values (and "magenta: NaN" under it when the slice has NaN), and a
// title. `snapfit fields --png`, `snapfit map --png` and report.html use it.
#include <optional>
#include <string>
#include <vector>

#include "snapfit/grid.h"
#include "snapfit/mesh.h"
#include "snapfit/slice_image.h"

namespace snapfit {

struct SliceFigureOptions {
  std::string title;
  std::string units;                      // axis labels "x (units)"
  std::string value_label;                // beside the colour bar
  std::vector<OutlineSegment> outline;    // (u, v) in scene units, drawn black on white
  int pixels_per_point = 0;               // 0: the field's longer side 480 pixels or more
  std::optional<double> symmetric_limit;  // render_slice's, for diverging maps
};

struct SliceFigure {
  SliceImage image;  // the whole figure; value_min / value_max: the colour bar's ends
  // Where the field is: grid point (col, row) of the slice (row 0 at the top) covers
  // pixels [left + col * scale, left + (col + 1) * scale) x [top + row * scale, ...).
  int left = 0, top = 0, scale = 1, columns = 0, rows = 0;
  // The colour bar: from bar_bottom (value_min) up to bar_top (value_max), bar_left to bar_right.
  int bar_left = 0, bar_right = 0, bar_top = 0, bar_bottom = 0;
  // Pixel position (x right, y down) of the point (u, v) of the slice plane, scene units.
  double u0 = 0, v0 = 0, spacing = 1;  // (u, v) of the slice's first grid point, and h
  double pixel_x(double u) const { return left + ((u - u0) / spacing + 0.5) * scale; }
  double pixel_y(double v) const { return top + rows * scale - ((v - v0) / spacing + 0.5) * scale; }
};

// The font the figures' labels are drawn in ("DejaVu Sans"), and "" when fontconfig finds
// it; otherwise what is missing and the package that has it. Without it cairo draws no
// readable labels.
std::string figure_font_problem();

// Throws snapfit::Error as render_slice does, and for pixels_per_point < 0.
SliceFigure render_slice_figure(const GridSpec& grid, const float* values, char axis, int index, ColorMap map,
                                const SliceFigureOptions& options);

// render_slice_figure written as a PNG at `path` with the text "Title" = "snapfit " + the
// title, and with `range_text` the colour bar's ends as "value_min" and "value_max".
// Throws snapfit::Error as render_slice_figure and write_png do.
SliceFigure write_slice_figure(const std::string& path, const GridSpec& grid, const float* values, char axis, int index,
                               ColorMap map, const SliceFigureOptions& options, bool range_text = false);

}  // namespace snapfit
