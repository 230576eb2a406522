// inspect_mesh_file (include/snapfit/inspect.h): a part file loaded through Assimp, or
// tessellated through OpenCASCADE for STEP and IGES, and validated.
#include "io/cad_load.h"
#include "io/mesh_load.h"
#include "mesh/mesh_report.h"
#include "snapfit/inspect.h"

namespace snapfit {

MeshFileReport inspect_mesh_file(const MeshFileRequest& request) {
  MeshFileReport report;
  if (!is_cad_file(request.file)) {
    report.mesh = validate_mesh(load_mesh(request.file, request.scale));
    return report;
  }
  CadImportOptions options;
  options.metres_per_unit = request.metres_per_unit;
  options.units = request.units;
  options.scale = request.scale;
  if (!request.solid.empty()) options.solid = request.solid;
  options.linear_deflection = request.deflection;
  options.angular_deflection_deg = request.angular_deflection_deg;
  if (request.spacing) {
    options.grid.spacing = *request.spacing;
  } else {
    options.grid.resolution = request.resolution;  // load_cad_mesh checks it
  }
  const CadMesh cad = load_cad_mesh(request.file, options);
  report.mesh = validate_mesh(cad.mesh);
  report.cad = cad.facts;
  return report;
}

}  // namespace snapfit
