#pragma once
// Mesh export: binary STL and ASCII OBJ, each written atomically (a temporary file in
// the same folder, then rename), so a reader never sees a half-written file.
#include <string>

#include "mesh/mesh.h"

namespace snapfit {

// Binary STL: 80-byte header, uint32 triangle count, then per triangle the unit normal
// and three vertices as float32 and a uint16 attribute (0), little-endian.
// Coordinates are rounded to float32. Throws snapfit::Error naming `path` and the reason
// (bad index, non-finite vertex, unwritable folder, ...); no file is left behind then.
void write_stl(const Mesh& mesh, const std::string& path);

// ASCII OBJ: "v x y z" (17 significant digits, exact round trip) and "f i j k" (1-based).
void write_obj(const Mesh& mesh, const std::string& path);

}  // namespace snapfit
