// scene_part_fields (include/snapfit/fields.h) against the descriptors computed directly
// on the prepared part and grid (engine/fields/descriptors.h), the slice's plane and
// outline against io/png_export.h and mesh/mesh_slice.h, and its checks.
#include <doctest/doctest.h>

#include "engine/fields/descriptors.h"
#include "mesh/mesh_slice.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/error.h"
#include "snapfit/fields.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

TEST_CASE("scene_part_fields: the part's fields on its grid, and the slice's outline") {
  const Scene scene = test::shipped_scene("default.json");
  const test::CacheDirScope cache;
  PartFieldsRequest request;
  request.part = 2;
  request.slice = std::make_pair('z', 10.0);
  request.note = [](const std::string&) {};
  const ScenePartFields part = scene_part_fields(scene, request);
  const AssemblyPair pair = prepare_assembly_pair(scene);
  const GridSpec& grid = pair.grid(2);
  CHECK(part.grid.dims == grid.dims);
  CHECK(part.grid.origin.isApprox(grid.origin));
  CHECK(part.triangles == pair.part(2).mesh.triangles.size());
  CHECK(part.device == test::test_context().device.info.name);
  CHECK(!part.result.from_cache);

  const DescriptorFields direct = compute_descriptors(test::test_context(), pair.part(2).mesh, grid, scene.descriptor);
  const DescriptorFields& f = part.result.fields;
  REQUIRE(f.winding.size() == direct.winding.size());
  REQUIRE(f.skeletal_density.size() == direct.skeletal_density.size());
  for (std::size_t i = 0; i < f.winding.size(); i += 97) {
    CHECK(f.winding[i] == doctest::Approx(direct.winding[i]).epsilon(1e-4));
    CHECK(f.skeletal_density[i] == doctest::Approx(direct.skeletal_density[i]).epsilon(1e-3));
  }

  CHECK(part.slice_index == slice_index_for(grid, 'z', 10.0));
  CHECK(part.slice_plane == doctest::Approx(grid.origin.z() + grid.spacing * part.slice_index));
  CHECK(part.outline.size() == mesh_slice_outline(pair.part(2).mesh, 'z', part.slice_plane).size());
  CHECK(!part.outline.empty());

  // The second time, from the cache.
  CHECK(scene_part_fields(scene, request).result.from_cache);
}

TEST_CASE("scene_part_fields: a bad part or a slice outside the grid is refused before any device work") {
  const Scene scene = test::shipped_scene("default.json");
  PartFieldsRequest request;
  request.device = "no device is called this";  // never reached
  request.part = 0;
  CHECK_THROWS_WITH_AS(scene_part_fields(scene, request), doctest::Contains("part"), Error);
  request.part = 1;
  request.slice = std::make_pair('x', 1e6);
  CHECK_THROWS_WITH_AS(scene_part_fields(scene, request), doctest::Contains("outside the grid"), Error);
}
