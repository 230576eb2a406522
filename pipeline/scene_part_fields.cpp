// scene_part_fields (include/snapfit/fields.h): stage 1 of the pipeline
// (pipeline/assembly_pair.h) and stage 2 for one part, with the slice checked in between.
#include "core/progress.h"
#include "engine/runtime/device.h"
#include "mesh/mesh_slice.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/error.h"
#include "snapfit/fields.h"

namespace snapfit {

ScenePartFields scene_part_fields(const Scene& scene, const PartFieldsRequest& request) {
  if (request.part != 1 && request.part != 2)
    throw Error("fields: the part must be 1 or 2 (got " + std::to_string(request.part) + ")");
  AssemblyPair pair = prepare_assembly_pair(scene);
  ScenePartFields out;
  out.grid = pair.grid(request.part);
  if (request.slice) {  // fail before the long work
    const auto [axis, coordinate] = *request.slice;
    out.slice_index = slice_index_for(out.grid, axis, coordinate);
    out.slice_plane = out.grid.origin[axis - 'x'] + out.grid.spacing * out.slice_index;
    out.outline = mesh_slice_outline(pair.part(request.part).mesh, axis, out.slice_plane);
  }
  out.triangles = pair.part(request.part).mesh.triangles.size();
  const ComputeContext ctx = make_compute_context(select_device(device_spec_from(request.device)));
  out.device = ctx.device.info.name;
  PairOptions options;
  if (request.progress) options.descriptors.progress = pass_progress_bars();
  options.use_cache = request.use_cache;
  options.note = request.note;
  compute_assembly_fields(pair, ctx, options, request.part);
  out.result = pair.fields(request.part);
  return out;
}

}  // namespace snapfit
