// translational_energy_map (include/snapfit/maps.h) on a public Assembly against per-pose
// queries of the same assembly at the map's grid translations (every mode, tricubic).
#include <cmath>
#include <doctest/doctest.h>

#include "snapfit/assembly.h"
#include "snapfit/maps.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

TEST_CASE("translational_energy_map: the assembly's map equals its per-pose queries") {
  AssemblyOptions options;
  options.note = [](const std::string&) {};
  const Assembly assembly(test::shipped_scene("peg_hole_translation.json"), options);
  const TranslationMap map = translational_energy_map(assembly, {});
  REQUIRE(map.energy.size() == map.grid.count());
  CHECK(map.grid.spacing == doctest::Approx(assembly.spacing()));
  auto engine = assembly.make_query_engine(assembly.query_variant(Interpolation::tricubic));
  engine->set_modes(engine->max_modes());
  double scale = 0;
  for (float e : map.energy)
    if (std::isfinite(e)) scale = std::max(scale, std::abs(static_cast<double>(e)));
  REQUIRE(scale > 0);
  int checked = 0;
  for (const Eigen::Vector3d target : {Eigen::Vector3d(0, 0, 5), Eigen::Vector3d(1, 0, 1), Eigen::Vector3d(0, 0, -8),
                                       Eigen::Vector3d(3, -2, 12), Eigen::Vector3d(0.5, 0, -2)}) {
    const Eigen::Vector3i idx = ((target - map.grid.origin) / map.grid.spacing).array().round().cast<int>();
    Pose pose;
    pose.translation = map.grid.point(idx.x(), idx.y(), idx.z());
    const QueryResult r = engine->query(pose);
    const float e = map.energy[map.grid.index(idx.x(), idx.y(), idx.z())];
    if (r.flags & query_outside_grid) continue;
    CHECK(std::abs(e - r.energy) <= 1e-4 * scale);
    ++checked;
  }
  CHECK(checked >= 4);

  TranslationMapRequest low_pass;
  low_pass.modes = 5000;
  const TranslationMap smooth = translational_energy_map(assembly, low_pass);
  CHECK(smooth.grid.count() == map.grid.count());
}
