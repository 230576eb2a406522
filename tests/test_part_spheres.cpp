// decompose_part_spheres (include/snapfit/spheres.h) against Algorithm 1 run directly on
// the prepared part (engine/fields/sphere_decomposition.h), and its checks before the work.
#include <doctest/doctest.h>

#include "engine/fields/sphere_decomposition.h"
#include "pipeline/prepare_parts.h"
#include "snapfit/error.h"
#include "snapfit/spheres.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

TEST_CASE("decompose_part_spheres: the direct decomposition of the part, one level per tolerance") {
  const Scene scene = test::shipped_scene("default.json");
  PartSpheresRequest request;
  request.part = 2;
  request.tolerances = {1.0, 2.0};
  request.samples = 5000;
  std::vector<double> reported;
  const PartSpheres spheres = decompose_part_spheres(
      scene, request, [&](const SpheresAtTolerance& level) { reported.push_back(level.tolerance); });
  REQUIRE(spheres.levels.size() == 2);
  CHECK(reported == std::vector<double>{1.0, 2.0});
  const Mesh& peg = prepare_parts(scene).part2.mesh;
  for (const SpheresAtTolerance& level : spheres.levels) {
    CAPTURE(level.tolerance);
    SphereDecompositionParams params;
    params.tolerance = level.tolerance;
    const SphereDecomposition direct = decompose_part(test::test_context(), peg, scene.descriptor, params);
    CHECK(level.decomposition.balls.size() == direct.balls.size());
    CHECK(level.decomposition.epsilon == doctest::Approx(direct.epsilon));
    CHECK(level.error.samples == 5000);
    CHECK(level.error.solid_volume > 0);
  }
  // A coarser tolerance needs fewer balls.
  CHECK(spheres.levels[1].decomposition.balls.size() < spheres.levels[0].decomposition.balls.size());
}

TEST_CASE("decompose_part_spheres: a bad part or tolerance is refused before any device work") {
  const Scene scene = test::shipped_scene("default.json");
  PartSpheresRequest request;
  request.part = 3;
  CHECK_THROWS_WITH_AS(decompose_part_spheres(scene, request), doctest::Contains("part"), Error);
  request.part = 1;
  request.tolerances = {-1.0};
  request.device = "no device is called this";  // never reached
  CHECK_THROWS_AS(decompose_part_spheres(scene, request), Error);
}
