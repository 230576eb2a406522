#include "pipeline/part_mesh.h"

#include "io/mesh_load.h"
#include "mesh/procedural/procedural_parts.h"
#include "snapfit/error.h"

namespace snapfit {

Mesh build_part_mesh(const PartSpec& part) {
  try {
    if (part.mesh_path) return load_mesh(*part.mesh_path, part.mesh_scale);
    if (part.procedural) return make_procedural_part(*part.procedural);
  } catch (const Error& e) {
    throw Error("part '" + part.name + "': " + e.what());
  }
  throw Error("part '" + part.name + "' has neither a mesh file nor a procedural description");
}

}  // namespace snapfit
