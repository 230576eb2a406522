#include "pipeline/part_mesh.h"

#include "io/cad_load.h"
#include "io/mesh_load.h"
#include "mesh/procedural/procedural_parts.h"
#include "snapfit/error.h"

namespace snapfit {

PartMesh build_part_mesh(const PartSpec& part, const Scene& scene) {
  PartMesh out;
  try {
    if (part.mesh_path && is_cad_file(*part.mesh_path)) {
      CadImportOptions options;
      options.metres_per_unit = metres_per_unit(scene.units);
      options.units = scene.units;
      options.scale = part.mesh_scale;
      options.solid = part.cad.solid;
      options.linear_deflection = part.cad.deflection;
      if (part.cad.angular_deflection_deg) options.angular_deflection_deg = *part.cad.angular_deflection_deg;
      options.grid = scene.grid;
      CadMesh cad = load_cad_mesh(*part.mesh_path, options);
      out.mesh = std::move(cad.mesh);
      out.faces = std::move(cad.faces);
      out.cad = std::move(cad.facts);
      return out;
    }
    if (part.mesh_path) {
      out.mesh = load_mesh(*part.mesh_path, part.mesh_scale);
      return out;
    }
    if (part.procedural) {
      out.mesh = make_procedural_part(*part.procedural);
      out.faces = procedural_part_faces(*part.procedural);
      return out;
    }
  } catch (const Error& e) {
    throw Error("part '" + part.name + "': " + e.what());
  }
  throw Error("part '" + part.name + "' has neither a mesh file nor a procedural description");
}

}  // namespace snapfit
