#include "pipeline/assembly_pair.h"

#include <iostream>

#include "pipeline/compute_plan.h"
#include "pipeline/spectra_cache.h"

namespace snapfit {

AssemblyPair build_assembly_pair(const Scene& scene, const ComputeContext& ctx, const FftLibrary& fft,
                                 const PairOptions& options) {
  AssemblyPair pair;
  pair.scene = scene;
  pair.parts = prepare_parts(scene);
  // Translation-only motion keeps part 2 at its scene orientation: bake it into the
  // mesh, so the queries run at R = identity (no spectrum rotation at all).
  if (scene.motion == Motion::translation && !scene.part2.pose.rotation.toRotationMatrix().isIdentity(1e-12)) {
    for (Eigen::Vector3d& v : pair.parts.part2.mesh.vertices) v = scene.part2.pose.rotation * v;
  }
  const auto note = options.note ? options.note : [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  const ScenePartGrids grids = scene_part_grids(scene.grid, pair.parts.part1.mesh, pair.parts.part2.mesh);
  pair.fields1 = part_fields(ctx, pair.parts.part1.mesh, grids.part1, scene.descriptor, options.descriptors,
                             options.use_cache, note);
  pair.fields2 = part_fields(ctx, pair.parts.part2.mesh, grids.part2, scene.descriptor, options.descriptors,
                             options.use_cache, note);
  const ComputePlan plan = plan_computation(scene);
  const std::string key = options.use_cache ? spectra_cache_key(pair.fields1.fields, pair.fields2.fields,
                                                                  plan.torque_fields, options.spectrum)
                                            : std::string();
  if (auto cached = options.use_cache ? load_cached_spectra(key, note) : std::nullopt) {
    pair.spectra = std::move(*cached);
  } else {
    pair.spectra = compute_pair_spectra(fft, ctx, pair.fields1.fields, pair.fields2.fields, plan.torque_fields,
                                        options.spectrum);
    if (options.use_cache) save_cached_spectra(key, pair.spectra, note);
  }
  return pair;
}

QueryVariant query_variant_for(const Scene& scene, Interpolation interpolation) {
  const ComputePlan plan = plan_computation(scene);
  QueryVariant variant;
  variant.force = plan.force;
  variant.torque = plan.torque;
  variant.translation_only = !plan.rotation;
  variant.interpolation = interpolation;
  return variant;
}

}  // namespace snapfit
