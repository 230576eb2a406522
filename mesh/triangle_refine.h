#pragma once
// Splits triangles (longest-edge bisection) until every piece fits in a ball of
// `max_radius` around its centroid (refine_triangles, public in include/snapfit/mesh.h).
// The result is a triangle soup covering exactly the same surface with the same
// orientation: surface integrals are unchanged, but the descriptor hierarchy gets leaves
// small relative to the grid spacing, so the per-point adaptive splitting is needed only
// very close to the surface.
#include "snapfit/mesh.h"
