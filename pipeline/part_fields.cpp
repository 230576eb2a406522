#include "pipeline/part_fields.h"

#include "pipeline/field_cache.h"

namespace snapfit {

namespace {

Eigen::AlignedBox3d bounding_box(const Mesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(v);
  return box;
}

}  // namespace

ScenePartGrids scene_part_grids(const GridParams& params, const Mesh& part1, const Mesh& part2) {
  ScenePartGrids grids;
  grids.spacing = common_spacing(params, {bounding_box(part1), bounding_box(part2)});
  grids.part1 = part_grid(part1, params, grids.spacing);
  grids.part2 = part_grid(part2, params, grids.spacing);
  return grids;
}

GridSpec part_grid(const Mesh& mesh, const GridParams& params, double spacing) {
  const Eigen::AlignedBox3d box = bounding_box(mesh);
  GridParams fixed = params;
  fixed.spacing = spacing;
  fixed.resolution.reset();
  return make_grid(box, fixed);
}

PartFieldsResult part_fields(const ComputeContext& ctx, const Mesh& mesh, const GridSpec& grid,
                             const DescriptorParams& params, const DescriptorOptions& options, bool use_cache,
                             const std::function<void(const std::string&)>& note) {
  PartFieldsResult result;
  const std::string key = use_cache ? descriptor_cache_key(mesh, grid, params, options) : std::string();
  if (use_cache) {
    if (std::optional<DescriptorFields> cached = load_cached_descriptors(key, note)) {
      if (cached->winding.size() == grid.count()) {
        result.fields = std::move(*cached);
        result.fields.grid = grid;
        result.fields.params = params;
        result.from_cache = true;
        return result;
      }
      note("field cache entry holds " + std::to_string(cached->winding.size()) + " points, the grid has " +
           std::to_string(grid.count()) + "; recomputing");
    }
  }
  result.fields = compute_descriptors(ctx, mesh, grid, params, options);
  if (use_cache) save_cached_descriptors(key, result.fields, note);
  return result;
}

}  // namespace snapfit
