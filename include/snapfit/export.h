#pragma once
// Files snapfit writes: grid fields as VTK XML ImageData (.vti) and point sets as VTK XML
// PolyData (.vtp) for ParaView and VisIt, meshes as STL and OBJ, and any text. Each is
// written to a temporary beside `path` and renamed onto it, so readers never see half a
// file; the parent folder must exist.
#include <Eigen/Core>
#include <string>
#include <vector>

#include "snapfit/grid.h"
#include "snapfit/mesh.h"

namespace snapfit {

// One field sampled on every grid point, in grid order (i fastest); a point's
// `components` values are adjacent (x y z for a vector). `values` must hold
// grid.count() * components floats and stay valid during write_vti.
struct GridField {
  std::string name;
  const float* values = nullptr;
  int components = 1;
};

// Throws snapfit::Error naming `path` for an empty or malformed grid (a dim < 1,
// spacing not positive, origin not finite), no fields, a field with an empty or
// duplicate name, null values or components outside 1..9, and for I/O failures; no
// file is left behind then.
void write_vti(const std::string& path, const GridSpec& grid, const std::vector<GridField>& fields);

struct PointScalars {
  std::string name;
  std::vector<double> values;  // one per point
};

// One Piece of a .vtp file: each point a vertex cell, with named per-point scalars (a
// ball's radius: ParaView's Glyph filter with a sphere source, "Scale Array" radius and
// scale factor 2, draws the balls). ASCII.
struct PointPiece {
  std::vector<Eigen::Vector3d> points;
  std::vector<PointScalars> scalars;  // the same names in every piece
};

// Throws snapfit::Error naming `path` for no pieces, a non-finite coordinate or value,
// scalars whose count differs from the points', pieces whose scalar names differ, and
// for I/O failures.
void write_points_vtp(const std::string& path, const std::vector<PointPiece>& pieces);

// Binary STL: 80-byte header, uint32 triangle count, then per triangle the unit normal
// and three vertices as float32 and a uint16 attribute (0), little-endian.
// Coordinates are rounded to float32. Throws snapfit::Error naming `path` and the reason
// (bad index, non-finite vertex, unwritable folder, ...); no file is left behind then.
void write_stl(const Mesh& mesh, const std::string& path);

// ASCII OBJ: "v x y z" (17 significant digits, exact round trip) and "f i j k" (1-based).
void write_obj(const Mesh& mesh, const std::string& path);

// Writes `text` as the whole file, through a temporary renamed onto `path`. Throws
// snapfit::Error "<path>: cannot write file: <reason>"; no file is left behind then.
void write_text_file(const std::string& path, const std::string& text);

// Text inside XML or HTML (element content and quoted attribute values): & < > " ' as
// &amp; &lt; &gt; &quot; &apos;, everything else as it is.
std::string escape_markup(const std::string& text);

}  // namespace snapfit
