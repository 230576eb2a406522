// Colour-mapped grid slices as PNG (io/png_export.h).
#include "io/png_export.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <png.h>
#include <string>
#include <unistd.h>

#include "io/atomic_write.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr long long kMaxSide = 1000000;  // libpng's default limit for readers

using Rgb = std::array<unsigned char, 3>;
constexpr Rgb kMagenta = {255, 0, 255};

std::string num(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

// 0, 1, 2 for 'x', 'y', 'z'.
int axis_number(char axis, const std::string& who) {
  if (axis == 'x' || axis == 'y' || axis == 'z') return axis - 'x';
  throw Error(who + ": axis must be 'x', 'y' or 'z', not '" + std::string(1, axis) + "'");
}

unsigned char channel(double c) { return static_cast<unsigned char>(std::lround(std::clamp(c, 0.0, 255.0))); }

// t in [-1, 1]: blue - white - red.
Rgb diverging(double t) {
  const double w = 255.0 * (1.0 - std::abs(t));
  return t < 0 ? Rgb{channel(w), channel(w), 255} : Rgb{255, channel(w), channel(w)};
}

// t in [0, 1]: matplotlib's viridis sampled at every 10%.
Rgb sequential(double t) {
  static constexpr unsigned char kStops[11][3] = {{68, 1, 84},    {72, 36, 117},  {65, 68, 135},  {53, 95, 141},
                                                  {42, 120, 142}, {33, 145, 140}, {34, 168, 132}, {68, 191, 112},
                                                  {122, 209, 81}, {189, 223, 38}, {253, 231, 37}};
  const double pos = std::clamp(t, 0.0, 1.0) * 10.0;
  const int i = std::min(static_cast<int>(pos), 9);
  const double f = pos - i;
  Rgb c;
  for (int k = 0; k < 3; ++k) c[k] = channel(kStops[i][k] + f * (kStops[i + 1][k] - kStops[i][k]));
  return c;
}

// Everything encode_png reads; it lives in the caller's frame, so libpng's longjmp
// skips no destructors.
struct PngJob {
  const SliceImage* image = nullptr;
  png_text* text = nullptr;
  int text_count = 0;
  char error[256] = {};
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* job = static_cast<PngJob*>(png_get_error_ptr(png));
  std::snprintf(job->error, sizeof job->error, "libpng: %s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// False with job->error set on failure. No objects with destructors in this frame.
bool encode_png(std::FILE* f, PngJob* job) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, job, on_png_error, on_png_warning);
  if (png == nullptr) {
    std::snprintf(job->error, sizeof job->error, "libpng: cannot create the writer");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (info == nullptr) {
    png_destroy_write_struct(&png, nullptr);
    std::snprintf(job->error, sizeof job->error, "libpng: cannot create the info block");
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  const SliceImage& im = *job->image;
  png_init_io(png, f);
  png_set_IHDR(png, info, static_cast<png_uint_32>(im.width), static_cast<png_uint_32>(im.height), 8,
               PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (job->text_count > 0) png_set_text(png, info, job->text, job->text_count);
  png_write_info(png, info);
  const std::size_t stride = 3 * static_cast<std::size_t>(im.width);
  for (int row = 0; row < im.height; ++row) png_write_row(png, im.rgb.data() + stride * static_cast<std::size_t>(row));
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

// PNG keywords: 1-79 printable Latin-1 characters, no leading, trailing or double spaces.
void check_keyword(const std::string& path, const std::string& key) {
  bool ok = !key.empty() && key.size() <= 79 && key.front() != ' ' && key.back() != ' ' &&
            key.find("  ") == std::string::npos;
  for (unsigned char c : key) ok = ok && ((c >= 32 && c <= 126) || c >= 161);
  if (!ok)
    throw Error(path + ": cannot write PNG: text keyword '" + key +
                "' is not 1-79 printable Latin-1 characters without leading, trailing or double spaces");
}

}  // namespace

SliceImage render_slice(const GridSpec& grid, const float* values, char axis, int index, ColorMap map,
                        std::optional<double> symmetric_limit, int scale) {
  const std::string who = "render_slice";
  const int a = axis_number(axis, who);
  const Eigen::Vector3i& d = grid.dims;
  if (d.x() < 1 || d.y() < 1 || d.z() < 1)
    throw Error(who + ": empty grid (dims " + std::to_string(d.x()) + " x " + std::to_string(d.y()) + " x " +
                std::to_string(d.z()) + ")");
  if (values == nullptr) throw Error(who + ": no values (null pointer)");
  if (index < 0 || index >= d[a])
    throw Error(who + ": " + std::string(1, axis) + " index " + std::to_string(index) +
                " is outside the grid, which has " + std::to_string(d[a]) + " points along " + std::string(1, axis) +
                " (0.." + std::to_string(d[a] - 1) + ")");
  if (symmetric_limit && !(*symmetric_limit > 0.0 && std::isfinite(*symmetric_limit)))
    throw Error(who + ": symmetric limit " + num(*symmetric_limit) + " is not a positive number");
  const int u = a == 0 ? 1 : 0;  // horizontal grid axis
  const int v = a == 2 ? 1 : 2;  // vertical grid axis, growing upward
  const int w = d[u], h = d[v];
  if (scale < 1 || static_cast<long long>(w) * scale > kMaxSide || static_cast<long long>(h) * scale > kMaxSide)
    throw Error(who + ": scale " + std::to_string(scale) + " must be at least 1 and keep each side of the " +
                std::to_string(w) + " x " + std::to_string(h) + " slice within " + std::to_string(kMaxSide) +
                " pixels");

  // The slice in image order (row 0 = top = largest index along v).
  std::vector<float> slice(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      int ijk[3];
      ijk[a] = index;
      ijk[u] = col;
      ijk[v] = h - 1 - row;
      slice[static_cast<std::size_t>(row) * w + col] = values[grid.index(ijk[0], ijk[1], ijk[2])];
    }

  double lo = 0, hi = 0, max_abs = 0;
  bool any = false;
  for (float x : slice)
    if (std::isfinite(x)) {
      lo = any ? std::min(lo, double(x)) : x;
      hi = any ? std::max(hi, double(x)) : x;
      max_abs = std::max(max_abs, std::abs(double(x)));
      any = true;
    }

  SliceImage image;
  image.width = w * scale;
  image.height = h * scale;
  image.rgb.resize(3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height));
  const double limit = symmetric_limit ? *symmetric_limit : max_abs;
  if (map == ColorMap::diverging) {
    image.value_min = -limit;
    image.value_max = limit;
  } else {
    image.value_min = lo;
    image.value_max = hi;
  }
  for (int row = 0; row < h; ++row)
    for (int col = 0; col < w; ++col) {
      const double x = slice[static_cast<std::size_t>(row) * w + col];
      const Rgb c = map_color(map, x, image.value_min, image.value_max);
      for (int dy = 0; dy < scale; ++dy) {
        unsigned char* p = image.rgb.data() + 3 * ((static_cast<std::size_t>(row) * scale + dy) * image.width +
                                                   static_cast<std::size_t>(col) * scale);
        for (int dx = 0; dx < scale; ++dx, p += 3) std::memcpy(p, c.data(), 3);
      }
    }
  return image;
}

std::array<unsigned char, 3> map_color(ColorMap map, double value, double value_min, double value_max) {
  if (std::isnan(value)) return kMagenta;
  if (map == ColorMap::diverging) {
    const double limit = value_max;
    return diverging(limit > 0 ? std::clamp(value / limit, -1.0, 1.0) : (value > 0 ? 1.0 : value < 0 ? -1.0 : 0.0));
  }
  const double lo = value_min, hi = value_max;
  return sequential(hi > lo ? (value - lo) / (hi - lo) : (value > hi ? 1.0 : 0.0));
}

namespace {

// Checks `image` and `text` (naming `who` in errors), then calls `encode` with the job
// that encode_png reads; the job's strings live until `encode` returns.
void with_png_job(const std::string& who, const SliceImage& image,
                  const std::vector<std::pair<std::string, std::string>>& text,
                  const std::function<void(PngJob&)>& encode) {
  if (image.width < 1 || image.height < 1 || image.width > kMaxSide || image.height > kMaxSide)
    throw Error(who + ": cannot write PNG: image size " + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " is not within 1.." + std::to_string(kMaxSide));
  const std::size_t bytes = 3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height);
  if (image.rgb.size() != bytes)
    throw Error(who + ": cannot write PNG: " + std::to_string(image.rgb.size()) + " bytes of RGB for a " +
                std::to_string(image.width) + " x " + std::to_string(image.height) + " image, which needs " +
                std::to_string(bytes));
  // libpng wants mutable C strings: copies that outlive encode_png.
  std::vector<std::string> keys, texts;
  for (const auto& [key, value] : text) {
    check_keyword(who, key);
    if (value.find('\0') != std::string::npos)
      throw Error(who + ": cannot write PNG: text for '" + key + "' contains a NUL byte");
    keys.push_back(key);
    texts.push_back(value);
  }
  std::vector<png_text> chunks(text.size());
  for (std::size_t t = 0; t < text.size(); ++t) {
    std::memset(&chunks[t], 0, sizeof chunks[t]);
    chunks[t].compression = PNG_TEXT_COMPRESSION_NONE;  // tEXt
    chunks[t].key = &keys[t][0];
    chunks[t].text = &texts[t][0];
    chunks[t].text_length = texts[t].size();
  }
  PngJob job;
  job.image = &image;
  job.text = chunks.data();
  job.text_count = static_cast<int>(chunks.size());
  encode(job);
}

// encode_png into `f`: "" or the reason it failed.
std::string encode_png_status(std::FILE* f, PngJob& job) {
  errno = 0;
  if (encode_png(f, &job)) return std::string();
  std::string problem = job.error;
  if (errno != 0) problem += std::string(" (") + std::strerror(errno) + ")";
  return problem;
}

}  // namespace

void write_png(const std::string& path, const SliceImage& image,
               const std::vector<std::pair<std::string, std::string>>& text) {
  with_png_job(path, image, text, [&](PngJob& job) {
    write_file_atomically(path, [&job](std::FILE* f) { return encode_png_status(f, job); });
  });
}

std::vector<unsigned char> png_bytes(const SliceImage& image,
                                     const std::vector<std::pair<std::string, std::string>>& text) {
  std::vector<unsigned char> out;
  with_png_job("png_bytes", image, text, [&](PngJob& job) {
    char* buffer = nullptr;
    std::size_t size = 0;
    std::FILE* f = open_memstream(&buffer, &size);
    if (f == nullptr) throw Error(std::string("png_bytes: cannot open a memory stream: ") + std::strerror(errno));
    const std::string problem = encode_png_status(f, job);
    std::fclose(f);  // sets buffer and size
    if (problem.empty()) out.assign(buffer, buffer + size);
    std::free(buffer);
    if (!problem.empty()) throw Error("png_bytes: cannot encode PNG: " + problem);
  });
  return out;
}

int slice_index_for(const GridSpec& grid, char axis, double coordinate) {
  const int a = axis_number(axis, "slice_index_for");
  const std::string name(1, axis);
  const int n = grid.dims[a];
  if (n < 1) throw Error("slice_index_for: the grid is empty along " + name);
  const double lo = grid.origin[a];
  const double hi = lo + grid.spacing * (n - 1);
  const double tol = 1e-9 * grid.spacing;  // rounding in the caller's coordinates
  if (!(coordinate >= lo - tol && coordinate <= hi + tol))
    throw Error(name + "=" + num(coordinate) + " is outside the grid, which spans " + name + " in [" + num(lo) + ", " +
                num(hi) + "]");
  const long nearest = n == 1 ? 0 : std::lround((coordinate - lo) / grid.spacing);
  return static_cast<int>(std::clamp<long>(nearest, 0, n - 1));
}

}  // namespace snapfit
