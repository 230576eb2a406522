#pragma once
// Point sets as VTK XML PolyData (.vtp) for ParaView: one Piece per set, each point a
// vertex cell, with named per-point scalars (e.g. a ball's radius: ParaView's Glyph filter
// with a sphere source, "Scale Array" radius and scale factor 2, draws the balls).
// ASCII, written atomically (io/atomic_write.h).
#include <Eigen/Core>
#include <string>
#include <vector>

namespace snapfit {

struct PointScalars {
  std::string name;
  std::vector<double> values;  // one per point
};

struct PointPiece {
  std::vector<Eigen::Vector3d> points;
  std::vector<PointScalars> scalars;  // the same names in every piece
};

// Throws snapfit::Error naming `path` for no pieces, a non-finite coordinate or value,
// scalars whose count differs from the points', pieces whose scalar names differ, and
// for I/O failures.
void write_points_vtp(const std::string& path, const std::vector<PointPiece>& pieces);

}  // namespace snapfit
