#pragma once
// The pipeline from a scene to what the per-frame queries need, in three stages that
// every command, benchmark and test goes through (so they all see the same parts,
// grids, fields and spectra):
//   1. prepare_assembly_pair: both parts built and validated (in parallel), in the
//      frames the queries use; the compute plan; both grids at one spacing (no device);
//   2. compute_assembly_fields: each part's descriptor fields (field cache, else computed);
//   3. compute_assembly_spectra: both parts' spectra (spectra cache, else computed).
// build_assembly_pair runs all three:
//
//   FftLibrary fft;
//   ComputeContext ctx = make_compute_context(select_device(""));
//   AssemblyPair pair = build_assembly_pair(load_scene("scenes/default.json"), ctx, fft);
//   auto engine = make_query_engine(ctx, pair.spectra, query_variant_for(pair.scene));
//   engine->set_modes(32768);
//   QueryResult r = engine->query(pose_of_part2_in_part1_frame);   // r.energy, r.force, r.torque
//
// Frames and signs: include/snapfit/query.h.
#include <functional>
#include <string>

#include "engine/spectra/fft3d.h"
#include "engine/query/near_field.h"
#include "engine/spectra/spectra.h"
#include "pipeline/compute_plan.h"
#include "pipeline/part_fields.h"
#include "pipeline/prepare_parts.h"
#include "pipeline/reach_region.h"
#include "snapfit/collision.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

struct PairOptions {
  SpectrumOptions spectrum;
  DescriptorOptions descriptors;
  // Also the near field of the split sum (engine/query/near_field.h, QueryVariant::near_far)
  // for a 6-DOF pair whose spectra come from both grids; seconds and tens of MB, so only
  // where a near-far strategy may run.
  bool near_field = false;
  NearFieldOptions near;
  bool use_cache = true;
  std::function<void(const std::string&)> note;  // cache messages; default: stderr
};

struct AssemblyPair {
  Scene scene;
  ComputePlan plan;
  // Part 2's mesh is in the frame its queries use: for translation-only motion, part 2
  // keeps its scene orientation, which is baked into the mesh (the queries then run at
  // R = identity, with no spectrum rotation at all).
  PreparedParts parts;
  ScenePartGrids grids;
  // Where part 2 can reach: part 1's grid covers it (grids.part1 is cropped to it, and
  // part 1's fields fade to zero outside it); not bounded: all of part 1.
  ReachRegion region;
  PartFieldsResult fields1, fields2;  // empty until stage 2
  PairSpectra spectra;                // empty until stage 3
  bool spectra_from_cache = false;

  const PartFieldsResult& fields(int part) const { return part == 1 ? fields1 : fields2; }
  const PreparedPart& part(int part) const { return part == 1 ? parts.part1 : parts.part2; }
  const GridSpec& grid(int part) const { return part == 1 ? grids.part1 : grids.part2; }
};

// Stage 1. Throws snapfit::Error naming the part when a mesh cannot be made.
AssemblyPair prepare_assembly_pair(const Scene& scene);

// Stage 2 for part 1, part 2, or both (which = 0). Throws snapfit::Error for a device failure.
void compute_assembly_fields(AssemblyPair& pair, const ComputeContext& ctx, const PairOptions& options = {},
                             int which = 0);

// Stage 3 (needs both parts' fields), with part 2's deconvolved spectrum when the plan
// rotates it (6-DOF motion).
void compute_assembly_spectra(AssemblyPair& pair, const ComputeContext& ctx, const FftLibrary& fft,
                              const PairOptions& options = {});

// All three stages.
AssemblyPair build_assembly_pair(const Scene& scene, const ComputeContext& ctx, const FftLibrary& fft,
                                 const PairOptions& options = {});

// The query variant a scene needs: its outputs and motion, with the given interpolation.
QueryVariant query_variant_for(const Scene& scene, Interpolation interpolation = Interpolation::tricubic);

}  // namespace snapfit
