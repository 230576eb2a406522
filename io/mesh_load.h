#pragma once
// Mesh import through Assimp: any format it reads (STL, OBJ, PLY, glTF, OFF, ...).
#include <string>

#include "io/mesh.h"

namespace snapfit {

// Loads every triangle of every mesh in the file, with node transforms applied, merged
// into one triangle soup, each coordinate multiplied by `scale` (file units -> scene
// units). Throws snapfit::Error naming the file and the problem for a missing,
// unreadable, empty or malformed file, a file with no triangles, or non-finite coordinates.
Mesh load_mesh(const std::string& path, double scale = 1.0);

}  // namespace snapfit
