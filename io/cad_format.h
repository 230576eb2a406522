#pragma once
// Which part files are CAD files (STEP, IGES), by their name: the scene reader, the part
// builder and `snapfit mesh-info` choose OpenCASCADE (io/cad_load.h) over Assimp by it.
#include <string>

#include "snapfit/inspect.h"

namespace snapfit {

// The format a file name says (its extension, any case): .step and .stp are STEP, .iges
// and .igs IGES; anything else is none. is_cad_file: STEP or IGES.
enum class CadFormat { none, step, iges };
CadFormat cad_format(const std::string& path);
}  // namespace snapfit
