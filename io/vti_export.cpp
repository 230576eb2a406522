// VTK XML ImageData export (io/vti_export.h).
#include "io/vti_export.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <set>
#include <string>
#include <unistd.h>

#include "core/host_endian.h"
#include "core/markup_escape.h"
#include "io/atomic_write.h"
#include "io/file_error.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

std::string number(double x) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

void check_inputs(const std::string& path, const GridSpec& grid, const std::vector<GridField>& fields) {
  const Eigen::Vector3i& d = grid.dims;
  if (d.x() < 1 || d.y() < 1 || d.z() < 1)
    file_error(path, "cannot write VTI: empty grid (dims " + std::to_string(d.x()) + " x " + std::to_string(d.y()) +
                         " x " + std::to_string(d.z()) + ")");
  if (!(grid.spacing > 0.0) || !std::isfinite(grid.spacing))
    file_error(path, "cannot write VTI: grid spacing " + number(grid.spacing) + " is not a positive number");
  if (!grid.origin.allFinite()) file_error(path, "cannot write VTI: grid origin is not finite");
  if (fields.empty()) file_error(path, "cannot write VTI: no fields given");
  std::set<std::string> names;
  for (std::size_t f = 0; f < fields.size(); ++f) {
    const GridField& field = fields[f];
    const std::string which = "field " + std::to_string(f) + " '" + field.name + "'";
    if (field.name.empty()) file_error(path, "cannot write VTI: field " + std::to_string(f) + " has an empty name");
    if (!names.insert(field.name).second)
      file_error(path, "cannot write VTI: two fields are named '" + field.name + "'");
    if (field.values == nullptr) file_error(path, "cannot write VTI: " + which + " has no values (null pointer)");
    if (field.components < 1 || field.components > 9)
      file_error(path, "cannot write VTI: " + which + " has " + std::to_string(field.components) +
                           " components; 1 to 9 are allowed");
  }
}

bool put_u64(std::FILE* f, std::uint64_t v) {
  unsigned char b[8];
  for (int i = 0; i < 8; ++i) b[i] = static_cast<unsigned char>(v >> (8 * i));
  return std::fwrite(b, 1, 8, f) == 8;
}

// `n` floats as little-endian float32, swapped in chunks on a big-endian host.
bool put_floats(std::FILE* f, const float* v, std::size_t n) {
  if (host_is_little_endian()) return std::fwrite(v, sizeof(float), n, f) == n;
  unsigned char buf[4096];
  for (std::size_t start = 0; start < n; start += sizeof buf / 4) {
    const std::size_t m = std::min(n - start, sizeof buf / 4);
    for (std::size_t i = 0; i < m; ++i) {
      std::uint32_t bits;
      std::memcpy(&bits, v + start + i, 4);
      for (int b = 0; b < 4; ++b) buf[4 * i + b] = static_cast<unsigned char>(bits >> (8 * b));
    }
    if (std::fwrite(buf, 4, m, f) != m) return false;
  }
  return true;
}

}  // namespace

void write_vti(const std::string& path, const GridSpec& grid, const std::vector<GridField>& fields) {
  check_inputs(path, grid, fields);
  const Eigen::Vector3i& d = grid.dims;
  const std::string extent =
      "0 " + std::to_string(d.x() - 1) + " 0 " + std::to_string(d.y() - 1) + " 0 " + std::to_string(d.z() - 1);
  const std::string s = number(grid.spacing);

  // The first scalar and the first 3-vector become ParaView's active arrays.
  std::string active;
  for (const GridField& f : fields)
    if (f.components == 1) {
      active += " Scalars=\"" + escape_markup(f.name) + "\"";
      break;
    }
  for (const GridField& f : fields)
    if (f.components == 3) {
      active += " Vectors=\"" + escape_markup(f.name) + "\"";
      break;
    }

  std::string xml = "<?xml version=\"1.0\"?>\n";
  xml += "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n";
  xml += "  <ImageData WholeExtent=\"" + extent + "\" Origin=\"" + number(grid.origin.x()) + " " +
         number(grid.origin.y()) + " " + number(grid.origin.z()) + "\" Spacing=\"" + s + " " + s + " " + s + "\">\n";
  xml += "    <Piece Extent=\"" + extent + "\">\n";
  xml += "      <PointData" + active + ">\n";
  std::uint64_t offset = 0;
  std::vector<std::uint64_t> bytes(fields.size());
  for (std::size_t f = 0; f < fields.size(); ++f) {
    bytes[f] = static_cast<std::uint64_t>(grid.count()) * static_cast<std::uint64_t>(fields[f].components) * 4u;
    xml += "        <DataArray type=\"Float32\" Name=\"" + escape_markup(fields[f].name) + "\" NumberOfComponents=\"" +
           std::to_string(fields[f].components) + "\" format=\"appended\" offset=\"" + std::to_string(offset) +
           "\"/>\n";
    offset += 8 + bytes[f];
  }
  xml += "      </PointData>\n";
  xml += "      <CellData>\n      </CellData>\n";
  xml += "    </Piece>\n";
  xml += "  </ImageData>\n";
  xml += "  <AppendedData encoding=\"raw\">\n   _";
  const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";

  write_file_atomically(
      path, errno_status([&](std::FILE* out) {
        if (std::fwrite(xml.data(), 1, xml.size(), out) != xml.size()) return false;
        for (std::size_t f = 0; f < fields.size(); ++f) {
          if (!put_u64(out, bytes[f])) return false;
          if (!put_floats(out, fields[f].values, grid.count() * static_cast<std::size_t>(fields[f].components)))
            return false;
        }
        return std::fwrite(tail.data(), 1, tail.size(), out) == tail.size();
      }));
}

}  // namespace snapfit
