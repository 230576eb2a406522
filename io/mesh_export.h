#pragma once
// Mesh export: binary STL and ASCII OBJ, each written atomically (a temporary file in
// the same folder, then rename), so a reader never sees a half-written file (the public
// declarations: include/snapfit/export.h).
#include "snapfit/export.h"
