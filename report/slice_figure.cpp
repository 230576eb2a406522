#include "report/slice_figure.h"

#include <algorithm>
#include <cairo.h>
#include <cmath>
#include <filesystem>
#include <fontconfig/fontconfig.h>
#include <memory>

#include "report/axis_ticks.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr int kMarginLeft = 78, kMarginTop = 44, kMarginBottom = 58, kBarGap = 26, kBarWidth = 22, kBarLabels = 96;
constexpr double kFontSize = 13, kTitleSize = 15;
constexpr const char* kFontFamily = "DejaVu Sans";

using Surface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using Context = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

enum class Align { left, center, right };

// Text with its reference point at (x, y): horizontally aligned as asked, vertically centred.
void text(cairo_t* cr, const std::string& s, double x, double y, Align align, double size = kFontSize) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  const double dx = align == Align::left ? 0 : align == Align::center ? -e.x_advance / 2 : -e.x_advance;
  cairo_move_to(cr, x + dx, y - (e.y_bearing + e.height / 2));
  cairo_show_text(cr, s.c_str());
}

double text_width(cairo_t* cr, const std::string& s, double size) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  return e.x_advance;
}

void line(cairo_t* cr, double x0, double y0, double x1, double y1) {
  cairo_move_to(cr, x0, y0);
  cairo_line_to(cr, x1, y1);
  cairo_stroke(cr);
}

}  // namespace

std::string figure_font_problem() {
  FcPattern* pattern = FcNameParse(reinterpret_cast<const FcChar8*>(kFontFamily));
  if (!pattern) return "fontconfig cannot parse the font name " + std::string(kFontFamily);
  FcConfigSubstitute(nullptr, pattern, FcMatchPattern);
  FcDefaultSubstitute(pattern);
  FcResult result = FcResultNoMatch;
  FcPattern* match = FcFontMatch(nullptr, pattern, &result);
  FcPatternDestroy(pattern);
  std::string problem;
  FcChar8 *family = nullptr, *file = nullptr;
  if (!match || FcPatternGetString(match, FC_FAMILY, 0, &family) != FcResultMatch ||
      std::string(reinterpret_cast<const char*>(family)) != kFontFamily ||
      FcPatternGetString(match, FC_FILE, 0, &file) != FcResultMatch ||
      !std::filesystem::exists(reinterpret_cast<const char*>(file)))
    problem = std::string("the font ") + kFontFamily +
              " that figure labels are drawn in is not installed (Debian package fonts-dejavu-core)";
  if (match) FcPatternDestroy(match);
  return problem;
}

namespace {

// Part 2's outline, black on a white halo, clipped to the field.
void draw_outline(cairo_t* c, const SliceFigure& fig, int field_w, int field_h,
                  const std::vector<OutlineSegment>& outline) {
  cairo_save(c);
  cairo_rectangle(c, fig.left, fig.top, field_w, field_h);
  cairo_clip(c);
  cairo_set_line_cap(c, CAIRO_LINE_CAP_ROUND);
  for (const auto& [colour, width_px] : {std::pair{1.0, 3.5}, std::pair{0.0, 1.5}}) {
    cairo_set_source_rgb(c, colour, colour, colour);
    cairo_set_line_width(c, width_px);
    for (const OutlineSegment& s : outline) {
      cairo_move_to(c, fig.pixel_x(s.a.x()), fig.pixel_y(s.a.y()));
      cairo_line_to(c, fig.pixel_x(s.b.x()), fig.pixel_y(s.b.y()));
    }
    cairo_stroke(c);
  }
  cairo_restore(c);
}

// The frames of the field and the colour bar, their ticks and labels, the axis names and
// the value's label (and a note when the slice holds NaN).
void draw_frames_and_labels(cairo_t* c, const SliceFigure& fig, const GridSpec& grid, char axis, int field_w,
                            int field_h, double lo, double hi, const SliceFigureOptions& options,
                            const SliceImage& plain) {
  cairo_set_source_rgb(c, 0.1, 0.1, 0.1);
  cairo_set_line_width(c, 1);
  cairo_rectangle(c, fig.left - 0.5, fig.top - 0.5, field_w + 1, field_h + 1);
  cairo_rectangle(c, fig.bar_left - 0.5, fig.bar_top - 0.5, kBarWidth + 1, field_h + 1);
  cairo_stroke(c);
  cairo_select_font_face(c, kFontFamily, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  const double u_lo = fig.u0 - grid.spacing / 2, u_hi = fig.u0 + (fig.columns - 0.5) * grid.spacing;
  const double v_lo = fig.v0 - grid.spacing / 2, v_hi = fig.v0 + (fig.rows - 0.5) * grid.spacing;
  const AxisTicks ut = linear_ticks(u_lo, u_hi, std::max(2, field_w / 70));
  for (double t : ut.major) {
    const double x = std::round(fig.pixel_x(t)) + 0.5;
    line(c, x, fig.top + field_h, x, fig.top + field_h + 5);
    text(c, tick_label(t, ut.step), x, fig.top + field_h + 16, Align::center);
  }
  const AxisTicks vt = linear_ticks(v_lo, v_hi, std::max(2, field_h / 50));
  for (double t : vt.major) {
    const double y = std::round(fig.pixel_y(t)) + 0.5;
    line(c, fig.left - 5, y, fig.left, y);
    text(c, tick_label(t, vt.step), fig.left - 8, y, Align::right);
  }
  const int a = axis - 'x', u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;
  const std::string axis_names = "xyz";
  const std::string units = options.units.empty() ? "" : " (" + options.units + ")";
  text(c, std::string(1, axis_names[u]) + units, fig.left + field_w / 2.0, fig.top + field_h + 40, Align::center);
  cairo_save(c);
  cairo_translate(c, 18, fig.top + field_h / 2.0);
  cairo_rotate(c, -M_PI / 2);
  text(c, std::string(1, axis_names[v]) + units, 0, 0, Align::center);
  cairo_restore(c);
  if (hi > lo) {
    const AxisTicks bt = linear_ticks(lo, hi, std::max(2, field_h / 45));
    for (double t : bt.major) {
      const double y = std::round(fig.bar_bottom - (t - lo) / (hi - lo) * (fig.bar_bottom - fig.bar_top)) + 0.5;
      line(c, fig.bar_right, y, fig.bar_right + 5, y);
      text(c, tick_label(t, bt.step), fig.bar_right + 8, y, Align::left);
    }
  } else {
    text(c, tick_label(lo, 0), fig.bar_right + 8, fig.bar_bottom - 0.5, Align::left);
  }
  text(c, options.value_label, fig.bar_left, fig.top - 10, Align::left);
  bool any_nan = false;  // render_slice draws NaN magenta, a colour neither map uses
  for (std::size_t p = 0; p + 2 < plain.rgb.size() && !any_nan; p += 3)
    any_nan = plain.rgb[p] == 255 && plain.rgb[p + 1] == 0 && plain.rgb[p + 2] == 255;
  if (any_nan) text(c, "magenta: NaN", fig.bar_left, fig.bar_bottom + 16, Align::left);
}

// The image surface's pixels (xRGB, `stride` bytes a row) as RGB bytes.
void copy_pixels(const unsigned char* data, int stride, int width, int height, std::vector<unsigned char>& rgb) {
  rgb.resize(3 * static_cast<std::size_t>(width) * height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const std::uint32_t px = reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(y) * stride)[x];
      unsigned char* out = rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x);
      out[0] = (px >> 16) & 255;
      out[1] = (px >> 8) & 255;
      out[2] = px & 255;
    }
}

}  // namespace

SliceFigure render_slice_figure(const GridSpec& grid, const float* values, char axis, int index, ColorMap map,
                                const SliceFigureOptions& options) {
  if (options.pixels_per_point < 0)
    throw Error("slice figure: pixels per point must be 0 (automatic) or more, not " +
                std::to_string(options.pixels_per_point));
  // The slice at one pixel a point first: it checks the arguments and gives the sizes.
  const SliceImage plain = render_slice(grid, values, axis, index, map, options.symmetric_limit, 1);
  SliceFigure fig;
  fig.columns = plain.width;
  fig.rows = plain.height;
  fig.scale = options.pixels_per_point > 0
                  ? options.pixels_per_point
                  : std::clamp((480 + std::max(fig.columns, fig.rows) - 1) / std::max(fig.columns, fig.rows), 1, 64);
  const SliceImage field = render_slice(grid, values, axis, index, map, options.symmetric_limit, fig.scale);
  const int a = axis - 'x', u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;
  fig.u0 = grid.origin[u];
  fig.v0 = grid.origin[v];
  fig.spacing = grid.spacing;
  fig.left = kMarginLeft;
  fig.top = kMarginTop;
  const int field_w = field.width, field_h = field.height;
  fig.bar_left = fig.left + field_w + kBarGap;
  fig.bar_right = fig.bar_left + kBarWidth;
  fig.bar_top = fig.top;
  fig.bar_bottom = fig.top + field_h;
  int width = fig.bar_right + kBarLabels;
  const int height = fig.top + field_h + kMarginBottom;

  // Measure the title with a scratch context, so the figure is wide enough for it.
  {
    Surface scratch(cairo_image_surface_create(CAIRO_FORMAT_RGB24, 1, 1), cairo_surface_destroy);
    Context cr(cairo_create(scratch.get()), cairo_destroy);
    cairo_select_font_face(cr.get(), kFontFamily, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    width = std::max(width, static_cast<int>(std::ceil(text_width(cr.get(), options.title, kTitleSize))) + 24);
  }
  Surface surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, width, height), cairo_surface_destroy);
  if (cairo_surface_status(surface.get()) != CAIRO_STATUS_SUCCESS)
    throw Error("slice figure: cairo cannot make a " + std::to_string(width) + " x " + std::to_string(height) +
                " image: " + cairo_status_to_string(cairo_surface_status(surface.get())));
  Context cr(cairo_create(surface.get()), cairo_destroy);
  cairo_t* c = cr.get();
  cairo_set_source_rgb(c, 1, 1, 1);
  cairo_paint(c);

  // The field, pixel for pixel.
  cairo_surface_flush(surface.get());
  unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  for (int y = 0; y < field_h; ++y)
    for (int x = 0; x < field_w; ++x) {
      const unsigned char* p = field.rgb.data() + 3 * (static_cast<std::size_t>(y) * field_w + x);
      auto* out =
          reinterpret_cast<std::uint32_t*>(data + static_cast<std::size_t>(fig.top + y) * stride) + fig.left + x;
      *out = (std::uint32_t(p[0]) << 16) | (std::uint32_t(p[1]) << 8) | p[2];
    }
  cairo_surface_mark_dirty(surface.get());

  // The colour bar, one colour a pixel row from value_min at the bottom to value_max at the top.
  const double lo = field.value_min, hi = field.value_max;
  for (int y = fig.bar_top; y < fig.bar_bottom; ++y) {
    const double f = (fig.bar_bottom - 0.5 - y) / (fig.bar_bottom - fig.bar_top);
    const auto rgb = map_color(map, lo + f * (hi - lo), lo, hi);
    cairo_set_source_rgb(c, rgb[0] / 255.0, rgb[1] / 255.0, rgb[2] / 255.0);
    cairo_rectangle(c, fig.bar_left, y, kBarWidth, 1);
    cairo_fill(c);
  }

  draw_outline(c, fig, field_w, field_h, options.outline);

  draw_frames_and_labels(c, fig, grid, axis, field_w, field_h, lo, hi, options, plain);
  cairo_select_font_face(c, kFontFamily, CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  text(c, options.title, 12, 16, Align::left, kTitleSize);
  cairo_surface_flush(surface.get());

  fig.image.width = width;
  fig.image.height = height;
  fig.image.value_min = lo;
  fig.image.value_max = hi;
  copy_pixels(data, stride, width, height, fig.image.rgb);
  return fig;
}

SliceFigure write_slice_figure(const std::string& path, const GridSpec& grid, const float* values, char axis, int index,
                               ColorMap map, const SliceFigureOptions& options, bool range_text) {
  const SliceFigure figure = render_slice_figure(grid, values, axis, index, map, options);
  std::vector<std::pair<std::string, std::string>> text = {{"Title", "snapfit " + options.title}};
  if (range_text) {
    text.emplace_back("value_min", std::to_string(figure.image.value_min));
    text.emplace_back("value_max", std::to_string(figure.image.value_max));
  }
  write_png(path, figure.image, text);
  return figure;
}

}  // namespace snapfit
