// The peg and hole block read from STEP files give the wrench of the procedural ones
// (scenes/default.json's parts) within the tessellation error.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <string>
#include <vector>

#include "engine/query/query_engine.h"
#include "io/cad_load.h"
#include "mesh/mesh_report.h"
#include "pipeline/assembly_pair.h"
#include "tests/cad_fixtures.h"
#include "tests/descriptor_reference.h"
#include "tests/test_engine_support.h"

namespace snapfit {
namespace {

constexpr std::size_t kModes = 4096;

struct Wrenches {
  std::vector<double> energy;
  std::vector<Eigen::Vector3d> force, torque;
};

Wrenches query_all(const Scene& scene, const std::vector<Pose>& poses, AssemblyPair* kept = nullptr) {
  const FftLibrary fft;
  PairOptions options;
  options.note = [](const std::string&) {};
  AssemblyPair pair = build_assembly_pair(scene, test::test_context(), fft, options);
  auto engine = make_query_engine(test::test_context(), pair.spectra, query_variant_for(scene, Interpolation::tricubic),
                                  test::test_program_cache());
  engine->set_modes(kModes);
  Wrenches w;
  for (const Pose& p : poses) {
    const QueryResult r = engine->query(p);
    REQUIRE(r.flags == 0);
    w.energy.push_back(r.energy);
    w.force.push_back(r.force);
    w.torque.push_back(r.torque);
  }
  if (kept) *kept = std::move(pair);
  return w;
}

Pose pose(double x, double y, double z, double deg = 0, Eigen::Vector3d axis = Eigen::Vector3d::UnitY()) {
  Pose p;
  p.translation = {x, y, z};
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180.0, axis.normalized()));
  return p;
}

// Largest difference between two sets of wrenches, per quantity.
struct Difference {
  double energy = 0, force = 0, torque = 0;
};
Difference difference(const Wrenches& a, const Wrenches& b) {
  Difference d;
  for (std::size_t i = 0; i < a.energy.size(); ++i) {
    d.energy = std::max(d.energy, std::abs(a.energy[i] - b.energy[i]));
    d.force = std::max(d.force, (a.force[i] - b.force[i]).norm());
    d.torque = std::max(d.torque, (a.torque[i] - b.torque[i]).norm());
  }
  return d;
}

}  // namespace

TEST_CASE("cad wrench: STEP peg and hole block give the procedural parts' wrench within the tessellation error") {
  const test::CacheDirScope cache;
  const test::TempDir dir;
  const Scene procedural = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  const double spacing = *procedural.grid.spacing;
  const double deflection = kDefaultDeflectionPerSpacing * spacing;  // what the STEP parts get by default

  Scene step = procedural;
  for (PartSpec* part : {&step.part1, &step.part2}) {
    const std::string file = dir.file(part->procedural->type + ".step");
    test::write_cad_part(file, *part->procedural);
    part->mesh_path = file;
    part->procedural.reset();
  }

  // Poses in contact along the default trajectory: entering tilted, half-way, inserted.
  const std::vector<Pose> poses = {pose(1, 0, 1, 3), pose(0.5, 0, -2, 1.5),  pose(0.3, -0.2, -5, 1, {1, 1, 0}),
                                   pose(0, 0, -8),   pose(0.1, 0, -12, 0.5), pose(0, 0, -20)};
  AssemblyPair step_pair, procedural_pair;
  const Wrenches p = query_all(procedural, poses, &procedural_pair);
  const Wrenches s = query_all(step, poses, &step_pair);

  // The meshes: watertight, at the deflection the scene's spacing asks for, and within it
  // (plus the 64-gons' own sagitta) of the procedural ones.
  const double sagitta64 = 5.5 * (1 - std::cos(M_PI / 64));
  for (int k : {1, 2}) {
    CAPTURE(k);
    const PreparedPart& sp = step_pair.part(k);
    const PreparedPart& pp = procedural_pair.part(k);
    REQUIRE(sp.cad);
    CHECK(sp.cad->linear_deflection == doctest::Approx(deflection).epsilon(1e-15));
    CHECK(sp.report.watertight());
    CHECK(std::abs(sp.report.enclosed_volume - pp.report.enclosed_volume) <=
          sp.cad->exact_area * (deflection + sagitta64));
    double worst = 0;
    for (const Eigen::Vector3d& v : pp.mesh.vertices) worst = std::max(worst, test::reference_distance(sp.mesh, v));
    CHECK(worst <= deflection + 1e-9);  // the N-gons' vertices lie on the exact circles
  }

  // The tolerance: the tessellation moves the surface by at most the deflection d, so the
  // descriptors' transitions at the surface move by at most d/h of a grid cell, and the
  // energy and force by about that fraction of their scale along the trajectory (the
  // largest |E| and |F| over the poses). A force error acts on the peg's wall at most a
  // hole depth (20 mm) from part 2's origin, which bounds the torque error. At d = h/10 a
  // 29-gon's broken mirror symmetry gives the largest errors measured (docs/scenes.md
  // "CAD parts"), still within these bounds.
  const double fraction = deflection / spacing, lever = 20;
  double energy_scale = 0, force_scale = 0;
  for (std::size_t k = 0; k < poses.size(); ++k) {
    energy_scale = std::max(energy_scale, std::abs(p.energy[k]));
    force_scale = std::max(force_scale, p.force[k].norm());
  }
  const Difference e = difference(s, p);
  MESSAGE("deflection " << deflection << " (" << step_pair.part(1).mesh.triangles.size() << " + "
                        << step_pair.part(2).mesh.triangles.size() << " triangles): |dE| " << e.energy << " of "
                        << energy_scale << ", |dF| " << e.force << " of " << force_scale << ", |dT| " << e.torque);
  CHECK(e.energy <= fraction * energy_scale);
  CHECK(e.force <= fraction * force_scale);
  CHECK(e.torque <= fraction * force_scale * lever);
}

}  // namespace snapfit
