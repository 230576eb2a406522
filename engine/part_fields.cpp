#include "engine/part_fields.h"

#include "io/field_cache.h"

namespace snapfit {

GridSpec part_grid(const Mesh& mesh, const GridParams& params, double spacing) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3d& v : mesh.vertices) box.extend(v);
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
    auto cached = load_cached_descriptors(key, note);
    if (cached && cached->winding.size() != grid.count()) {
      note("field cache entry holds " + std::to_string(cached->winding.size()) + " points, the grid has " +
           std::to_string(grid.count()) + "; recomputing");
      cached.reset();
    }
    if (cached) {
      result.fields = std::move(*cached);
      result.fields.grid = grid;
      result.fields.params = params;
      result.from_cache = true;
      return result;
    }
  }
  result.fields = compute_descriptors(ctx, mesh, grid, params, options);
  if (use_cache) save_cached_descriptors(key, result.fields, note);
  return result;
}

}  // namespace snapfit
