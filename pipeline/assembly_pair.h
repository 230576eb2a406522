#pragma once
// The public entry point for a haptics program: build (or load from the caches) an
// assembly pair from a scene, then ask for energy, force and torque per pose.
//
//   FftLibrary fft;
//   ComputeContext ctx = make_compute_context(select_device(""));
//   AssemblyPair pair = build_assembly_pair(load_scene("scenes/default.json"), ctx, fft);
//   auto engine = make_query_engine(ctx, pair.spectra, query_variant_for(pair.scene));
//   engine->set_modes(32768);
//   QueryResult r = engine->query(pose_of_part2_in_part1_frame);   // r.energy, r.force, r.torque
//
// Frames and signs: engine/pose_query.h.
#include <functional>
#include <string>

#include "pipeline/part_fields.h"
#include "snapfit/query.h"
#include "engine/query_engine.h"
#include "engine/spectra.h"
#include "snapfit/scene.h"
#include "pipeline/prepare_parts.h"

namespace snapfit {

struct PairOptions {
  SpectrumOptions spectrum;
  DescriptorOptions descriptors;
  bool use_cache = true;
  std::function<void(const std::string&)> note;  // cache messages; default: stderr
};

struct AssemblyPair {
  Scene scene;
  PreparedParts parts;
  PartFieldsResult fields1, fields2;
  PairSpectra spectra;
};

// Parts, descriptor fields (cached) and spectra, with only what the scene needs
// (torque spectra only when the scene asks for torque with 6-DOF motion).
AssemblyPair build_assembly_pair(const Scene& scene, const ComputeContext& ctx, const FftLibrary& fft,
                                 const PairOptions& options = {});

// The query variant a scene needs: its outputs and motion, with the given interpolation.
QueryVariant query_variant_for(const Scene& scene, Interpolation interpolation = Interpolation::tricubic);

}  // namespace snapfit
