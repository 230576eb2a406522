#pragma once
// Validation report of a triangle mesh: what `snapfit mesh-info` prints.
#include <Eigen/Core>
#include <cstddef>
#include <string>

#include "mesh/mesh.h"
#include "snapfit/inspect.h"

namespace snapfit {

// Vertices at identical positions are welded before edges are counted, so a triangle
// soup (STL) is judged by its geometry, not by its index buffer.
MeshReport validate_mesh(const Mesh& mesh);

}  // namespace snapfit
