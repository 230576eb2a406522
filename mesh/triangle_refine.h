#pragma once
// Splits triangles (longest-edge bisection) until every piece fits in a ball of
// `max_radius` around its centroid. The result is a triangle soup covering exactly
// the same surface with the same orientation: surface integrals are unchanged, but the
// descriptor hierarchy gets leaves small relative to the grid spacing, so the
// per-point adaptive splitting is needed only very close to the surface.
#include "mesh/mesh.h"

namespace snapfit {

// Throws snapfit::Error when max_radius is not positive or the result would exceed
// `max_triangles` (the caller should use a coarser grid or a larger radius).
Mesh refine_triangles(const Mesh& mesh, double max_radius, std::size_t max_triangles = 20000000);

}  // namespace snapfit
