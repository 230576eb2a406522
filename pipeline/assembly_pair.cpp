#include "pipeline/assembly_pair.h"

#include <iostream>
#include <sstream>

#include "pipeline/spectra_cache.h"
#include "pipeline/sphere_spectra.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

std::function<void(const std::string&)> note_of(const PairOptions& options) {
  if (options.note) return options.note;
  return [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
}

}  // namespace

AssemblyPair prepare_assembly_pair(const Scene& scene) {
  AssemblyPair pair;
  pair.scene = scene;
  pair.plan = plan_computation(scene);
  pair.parts = prepare_parts(scene);
  if (scene.motion == Motion::translation && !scene.part2.pose.rotation.toRotationMatrix().isIdentity(1e-12)) {
    for (Eigen::Vector3d& v : pair.parts.part2.mesh.vertices) v = scene.part2.pose.rotation * v;
    const Eigen::Matrix3d turn = scene.part2.pose.rotation.toRotationMatrix();
    for (AnalyticFace& f : pair.parts.part2.faces) f = rotated_face(f, turn);
  }
  try {
    pair.grids = scene_part_grids(scene.grid, pair.parts.part1.mesh, pair.parts.part2.mesh);
  } catch (const Error& e) {
    // Too many grid points usually means a part far larger than intended: say how large.
    std::ostringstream m;
    m << e.what() << " (the parts come out as";
    for (const auto& [spec, part] : {std::pair{&scene.part1, &pair.parts.part1}, {&scene.part2, &pair.parts.part2}}) {
      const Eigen::Vector3d size = part->report.bbox_max - part->report.bbox_min;
      m << " '" << spec->name << "' " << size.x() << " x " << size.y() << " x " << size.z() << " " << scene.units
        << (spec == &scene.part1 ? "," : "");
    }
    m << "; if one should be smaller, its file's unit, \"mesh_units\" or \"scale\" is wrong)";
    throw Error(m.str());
  }
  if (uses_vps(scene.method)) pair.plan = plan_computation(scene, pair.grids.spacing);
  pair.region = scene_region(scene, pair.grids.part1, pair.grids.part2);
  pair.grids.part1 = pair.region.part1_grid;
  if (!uses_vps(scene.method)) pair.plan.lines.push_back(pair.region.reason);
  return pair;
}

void compute_assembly_fields(AssemblyPair& pair, const ComputeContext& ctx, const PairOptions& options, int which) {
  if (which < 0 || which > 2)
    throw Error("compute_assembly_fields: part must be 1, 2 or 0 for both (got " + std::to_string(which) + ")");
  const auto note = note_of(options);
  for (int part = 1; part <= 2; ++part) {
    if (which != 0 && which != part) continue;
    PartFieldsResult& out = part == 1 ? pair.fields1 : pair.fields2;
    out = part_fields(ctx, pair.part(part).mesh, pair.grid(part), pair.scene.descriptor, options.descriptors,
                      options.use_cache, note);
    // Outside the region part 1's affinity fades to zero (pipeline/reach_region.h); the
    // indicator's is a threshold of w, so it is cut at the grid's edge instead.
    if (part == 1 && pair.region.bounded && !out.fields.skeletal_density.empty())
      fade_outside(out.fields.grid, pair.region.box, pair.region.fade, out.fields.skeletal_density);
  }
}

void compute_assembly_spectra(AssemblyPair& pair, const ComputeContext& ctx, const FftLibrary& fft,
                              const PairOptions& options) {
  if (pair.fields1.fields.winding.empty() || pair.fields2.fields.winding.empty())
    throw Error("compute_assembly_spectra: both parts' fields are needed first (compute_assembly_fields)");
  const auto note = note_of(options);
  SpectrumOptions spectrum = options.spectrum;
  if (!pair.plan.rotation) spectrum.exact_rotation_width = 0;  // part 2 never turns
  const PartDescriptorSpec& source1 = pair.scene.part1.descriptor;
  const PartDescriptorSpec& source2 = pair.scene.part2.descriptor;
  const std::string key = options.use_cache ? spectra_cache_key(pair.fields1.fields, pair.fields2.fields, spectrum,
                                                                spectrum_source_key(source1, pair.grids.spacing),
                                                                spectrum_source_key(source2, pair.grids.spacing))
                                            : std::string();
  pair.spectra_from_cache = false;
  const bool spheres = source1.source == SpectrumSource::spheres || source2.source == SpectrumSource::spheres;
  if (auto cached = options.use_cache ? load_cached_spectra(key, note) : std::nullopt) {
    pair.spectra = std::move(*cached);
    pair.spectra_from_cache = true;
  } else {
    if (spheres)
      pair.spectra = compute_sphere_pair_spectra(pair, ctx, fft, spectrum, options.descriptors, note);
    else
      pair.spectra = compute_pair_spectra(fft, ctx, pair.fields1.fields, pair.fields2.fields, spectrum);
    if (options.use_cache) save_cached_spectra(key, pair.spectra, note);
  }
  // The near part sums part 2's grid samples, the ones its spectrum was made from, over
  // the region they can reach.
  if (options.near_field && pair.plan.rotation && !spheres && pair.spectra.conjugate_pairs()) {
    std::vector<Complex> rho2;
    for (float v : affinity_imaginary(pair.fields2.fields)) rho2.emplace_back(0.0f, v);
    NearFieldOptions near = options.near;
    if (!near.reach && pair.region.box_known) near.reach = pair.region.box;
    pair.spectra.near = std::make_shared<const NearField>(
        build_near_field(fft, ctx, pair.spectra, pair.fields2.fields.grid, rho2, near));
  }
}

AssemblyPair build_assembly_pair(const Scene& scene, const ComputeContext& ctx, const FftLibrary& fft,
                                 const PairOptions& options) {
  AssemblyPair pair = prepare_assembly_pair(scene);
  compute_assembly_fields(pair, ctx, options);
  compute_assembly_spectra(pair, ctx, fft, options);
  return pair;
}

Scene indicator_scene(const Scene& scene) {
  Scene s = scene;
  s.descriptor.kind = DescriptorKind::indicator;
  return s;
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
