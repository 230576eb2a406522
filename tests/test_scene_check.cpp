// check_scene (include/snapfit/inspect.h): both parts as the pipeline builds them, each
// report against a fresh validation of that mesh, the plan as planned, and a missing
// part named.
#include <doctest/doctest.h>

#include "mesh/mesh_report.h"
#include "pipeline/prepare_parts.h"
#include "snapfit/error.h"
#include "snapfit/inspect.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

TEST_CASE("check_scene: the parts' reports and the compute plan of a shipped scene") {
  for (const char* file : {"default.json", "peg_hole_step.json"}) {
    CAPTURE(file);
    const Scene scene = test::shipped_scene(file);
    const SceneCheck check = check_scene(scene);
    const PreparedParts parts = prepare_parts(scene);
    for (int part : {1, 2}) {
      const PartCheck& c = part == 1 ? check.part1 : check.part2;
      const MeshReport fresh = validate_mesh(part == 1 ? parts.part1.mesh : parts.part2.mesh);
      CHECK(c.mesh.triangle_count == fresh.triangle_count);
      CHECK(c.mesh.vertex_count == fresh.vertex_count);
      CHECK(c.mesh.enclosed_volume == doctest::Approx(fresh.enclosed_volume));
      CHECK(c.mesh.watertight());
      CHECK(c.seconds >= 0);
      CHECK(c.cad.has_value() == (part == 1 ? scene.part1 : scene.part2).mesh_path.has_value());
    }
    CHECK(!check.plan.empty());
  }
}

TEST_CASE("check_scene: a part whose file is missing is named") {
  Scene scene = test::shipped_scene("default.json");
  scene.part2.procedural.reset();
  scene.part2.mesh_path = "/nonexistent/peg.stl";
  CHECK_THROWS_WITH_AS(check_scene(scene), doctest::Contains("/nonexistent/peg.stl"), Error);
}
