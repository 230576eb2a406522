#pragma once
// Point sets as VTK XML PolyData (.vtp) for ParaView: one Piece per set, each point a
// vertex cell, with named per-point scalars (e.g. a ball's radius: ParaView's Glyph filter
// with a sphere source, "Scale Array" radius and scale factor 2, draws the balls).
// ASCII, written atomically (io/atomic_write.h).
#include <Eigen/Core>
#include <string>
#include <vector>

#include "snapfit/export.h"

namespace snapfit {

}  // namespace snapfit
