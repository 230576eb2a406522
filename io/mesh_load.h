#pragma once
// Mesh import through Assimp: any format it reads (STL, OBJ, PLY, glTF, OFF, ...).
#include <string>

#include "mesh/mesh.h"

namespace snapfit {

// Loads every triangle of every mesh in the file, with node transforms applied, merged
// into one triangle soup, each coordinate multiplied by `scale` (file units -> scene
// units). Throws snapfit::Error naming the file and the problem for a missing,
// unreadable, empty or malformed file, a file with no triangles, or non-finite coordinates.
// Assimp runs in a child process under a memory and time limit (io/import_child.h gives
// the defaults; SNAPFIT_IMPORT_MEMORY_MIB sets the memory limit in MiB, 0 or "inprocess"
// imports in this process): an importer that exceeds them or crashes is an Error too.
// STEP and IGES files are read by load_cad_mesh (io/cad_load.h), not here.
Mesh load_mesh(const std::string& path, double scale = 1.0);

}  // namespace snapfit
