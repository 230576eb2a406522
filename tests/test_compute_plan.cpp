// The compute plan (pipeline/compute_plan.h) on shipped scenes: what it decides, that no
// shipped scene is warned about, and the spectrum source each part takes.
#include <doctest/doctest.h>
#include <filesystem>

#include "pipeline/assembly_pair.h"

namespace snapfit {

TEST_CASE("compute plan: no shipped scene is warned about, at its own grid spacing or a coarser one") {
  // sigma is the Gaussian's width in eta/|xi| - 1, dimensionless: the skeletal density's
  // layer near the surface is sigma |xi| wide in scene units, whatever the grid, so no
  // comparison of sigma with a spacing in millimetres can say it is under-resolved.
  for (const auto& entry : std::filesystem::directory_iterator(std::string(SNAPFIT_SOURCE_DIR) + "/scenes")) {
    if (entry.path().extension() != ".json") continue;
    CAPTURE(entry.path().string());
    Scene scene = load_scene(entry.path().string());
    CHECK(prepare_assembly_pair(scene).plan.warnings.empty());
    if (scene.descriptor.kind != DescriptorKind::skeletal_density) continue;
    scene.grid.resolution.reset();
    scene.grid.spacing = 2 * scene.descriptor.sigma;  // once warned about, wrongly
    CHECK(prepare_assembly_pair(scene).plan.warnings.empty());
  }
}

TEST_CASE("compute plan: 6-DOF scenes get part 2's deconvolved spectrum and a torque, translation-only ones neither") {
  const Scene six = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  const ComputePlan p6 = plan_computation(six);
  CHECK(p6.rotation);
  CHECK(p6.torque);
  const Scene line = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/peg_hole_translation.json");
  const ComputePlan pt = plan_computation(line);
  CHECK_FALSE(pt.rotation);
  CHECK_FALSE(pt.torque);
}

TEST_CASE("compute plan: a part with spectra from balls is named, with the grid path recommended, grid scenes say so") {
  Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/collision_only.json");
  const ComputePlan grid = plan_computation(scene);
  CHECK(grid.warnings.empty());
  const auto has_line = [](const ComputePlan& plan, const std::string& text) {
    for (const std::string& line : plan.lines)
      if (line.find(text) != std::string::npos) return true;
    return false;
  };
  CHECK(has_line(grid, "spectrum source: the grid for both parts"));

  scene.part2.descriptor.source = SpectrumSource::spheres;
  scene.part2.descriptor.method = "direct";
  const ComputePlan balls = plan_computation(scene);
  CHECK(has_line(balls, "part 2's spectrum: seed 001's balls (tolerance the grid spacing, protrusion 0.25)"));
  CHECK(has_line(balls, "summed by the direct NDFT"));
  CHECK_FALSE(has_line(balls, "part 1's spectrum"));
  CHECK_FALSE(has_line(balls, "spectrum source: the grid for both parts"));
  REQUIRE(balls.warnings.size() == 1);
  CHECK(balls.warnings[0].find("part 2 takes its spectrum from balls") == 0);
  CHECK(balls.warnings[0].find("\"source\": \"grid\" is recommended") != std::string::npos);
}

}  // namespace snapfit
