// VTK XML PolyData export of point sets (io/vtp_export.h).
#include "io/vtp_export.h"

#include <cmath>
#include <cstdio>

#include "core/markup_escape.h"
#include "io/atomic_write.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

[[noreturn]] void vtp_error(const std::string& path, const std::string& problem) {
  throw Error(path + ": cannot write VTP: " + problem);
}

void put(std::string& out, double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g ", v);
  out += buf;
}

void check(const std::string& path, const std::vector<PointPiece>& pieces) {
  if (pieces.empty()) vtp_error(path, "no point sets given");
  for (std::size_t p = 0; p < pieces.size(); ++p) {
    const PointPiece& piece = pieces[p];
    for (const Eigen::Vector3d& q : piece.points)
      if (!q.allFinite()) vtp_error(path, "point set " + std::to_string(p) + " has a non-finite point");
    if (piece.scalars.size() != pieces[0].scalars.size())
      vtp_error(path, "point set " + std::to_string(p) + " has other scalars than point set 0");
    for (std::size_t s = 0; s < piece.scalars.size(); ++s) {
      const PointScalars& a = piece.scalars[s];
      if (a.name.empty() || a.name != pieces[0].scalars[s].name)
        vtp_error(path, "point set " + std::to_string(p) + " scalar " + std::to_string(s) + " '" + a.name +
                            "' is empty or named differently than in point set 0");
      if (a.values.size() != piece.points.size())
        vtp_error(path, "scalar '" + a.name + "' of point set " + std::to_string(p) + " has " +
                            std::to_string(a.values.size()) + " values for " + std::to_string(piece.points.size()) +
                            " points");
      for (double v : a.values)
        if (!std::isfinite(v)) vtp_error(path, "scalar '" + a.name + "' has a non-finite value");
    }
  }
}

}  // namespace

void write_points_vtp(const std::string& path, const std::vector<PointPiece>& pieces) {
  check(path, pieces);
  std::string out =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\">\n"
      "<PolyData>\n";
  for (const PointPiece& piece : pieces) {
    const std::size_t n = piece.points.size();
    out += "<Piece NumberOfPoints=\"" + std::to_string(n) + "\" NumberOfVerts=\"" + std::to_string(n) +
           "\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<PointData";
    if (!piece.scalars.empty()) out += " Scalars=\"" + escape_markup(piece.scalars[0].name) + "\"";
    out += ">\n";
    for (const PointScalars& a : piece.scalars) {
      out += "<DataArray type=\"Float64\" Name=\"" + escape_markup(a.name) + "\" format=\"ascii\">\n";
      for (double v : a.values) put(out, v);
      out += "\n</DataArray>\n";
    }
    out += "</PointData>\n<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Eigen::Vector3d& q : piece.points) {
      put(out, q.x());
      put(out, q.y());
      put(out, q.z());
    }
    out += "\n</DataArray>\n</Points>\n<Verts>\n<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (std::size_t i = 0; i < n; ++i) out += std::to_string(i) + " ";
    out += "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (std::size_t i = 1; i <= n; ++i) out += std::to_string(i) + " ";
    out += "\n</DataArray>\n</Verts>\n</Piece>\n";
  }
  out += "</PolyData>\n</VTKFile>\n";
  write_text_file(path, out);
}

}  // namespace snapfit
