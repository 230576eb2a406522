#pragma once
// Descriptor fields of one scene part: from the field cache when a matching entry
// exists, else computed (with progress) and cached.
#include <functional>
#include <string>

#include "engine/fields/descriptors.h"

namespace snapfit {

// `note` receives cache messages (stale or corrupt entries, write failures).
PartFieldsResult part_fields(const ComputeContext& ctx, const Mesh& mesh, const GridSpec& grid,
                             const DescriptorParams& params, const DescriptorOptions& options, bool use_cache,
                             const std::function<void(const std::string&)>& note);

// The grid of a part: its mesh's box grown by the scene's padding, at `spacing`.
GridSpec part_grid(const Mesh& mesh, const GridParams& params, double spacing);

// Both parts' grids at one common spacing (their spectra must share it).
struct ScenePartGrids {
  GridSpec part1, part2;
  double spacing = 0;
};
ScenePartGrids scene_part_grids(const GridParams& params, const Mesh& part1, const Mesh& part2);

}  // namespace snapfit
