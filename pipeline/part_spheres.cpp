// decompose_part_spheres (include/snapfit/spheres.h): a scene's part built by the pipeline's
// first stage, decomposed (engine/fields/sphere_decomposition.h) and measured
// (engine/fields/ball_union_error.h) at each tolerance.
#include "core/progress.h"
#include "engine/fields/ball_union_error.h"
#include "engine/fields/sphere_decomposition.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/error.h"
#include "snapfit/spheres.h"

namespace snapfit {

PartSpheres decompose_part_spheres(const Scene& scene, const PartSpheresRequest& request,
                                   const SpheresCallback& on_level) {
  if (request.part != 1 && request.part != 2)
    throw Error("spheres: the part must be 1 or 2 (got " + std::to_string(request.part) + ")");
  const AssemblyPair pair = prepare_assembly_pair(scene);
  const Mesh& mesh = pair.part(request.part).mesh;
  std::vector<double> tolerances = request.tolerances;
  if (tolerances.empty()) tolerances.push_back(pair.grids.spacing);                      // the scene's own resolution
  for (std::size_t i = 0; i < tolerances.size(); ++i) sphere_grid(mesh, tolerances[i]);  // fail before the work
  const ComputeContext ctx = make_compute_context(select_device(device_spec_from(request.device)));
  PartSpheres out;
  for (double tolerance : tolerances) {
    SphereDecompositionParams params;
    params.tolerance = tolerance;
    params.protrusion = request.protrusion;
    params.order = request.order;
    DescriptorOptions options;
    if (request.progress) options.progress = pass_progress_bars();
    SpheresAtTolerance level;
    level.tolerance = tolerance;
    level.decomposition = decompose_part(ctx, mesh, scene.descriptor, params, options);
    level.error = ball_union_error(ctx, mesh, level.decomposition.balls, request.samples);
    if (on_level) on_level(level);
    out.levels.push_back(std::move(level));
  }
  return out;
}

}  // namespace snapfit
