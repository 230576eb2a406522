// The per-query error estimate (engine/query/error_estimate.h): every engine's kernel returns,
// with its total, the sums over the two octave bands below the cut, modes (m'/4, m'/2]
// and (m'/2, m']; the estimate is kErrorEstimateScale times their root sum of squares.
// Checked against the same bands made independently, as differences of the engine's own
// queries at m'/4, m'/2 and m', on shipped parts (coarsened) at contact and generic
// poses, for the interpolated 6-DOF sum (folded and not), the exact-rotation product and
// the translation-only lines. How well the estimate covers the true error is measured by
// `snapfit accuracy` against the exact reference (docs/design.md "Error estimate").
#include <Eigen/Geometry>
#include <cmath>
#include <doctest/doctest.h>
#include <string>
#include <vector>

#include "engine/query/error_estimate.h"
#include "engine/query/query_engine.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/trajectory.h"
#include "tests/stability_support.h"

namespace snapfit {
namespace {

using Eigen::Vector3d;

struct Case {
  std::string name;
  QueryVariant variant;
};

void check_bands(const Scene& scene, const AssemblyPair& pair, const std::vector<Case>& cases,
                 const std::vector<Pose>& poses) {
  for (const Case& c : cases) {
    auto engine = make_query_engine(test::test_context(), pair.spectra, c.variant, test::test_program_cache());
    for (const std::size_t m : {std::size_t(4096), std::size_t(10001)}) {
      for (const Pose& pose : poses) {
        engine->set_modes(m);
        const QueryResult at = engine->query(pose);
        engine->set_modes(m / 2);
        const QueryResult half = engine->query(pose);
        engine->set_modes(m / 4);
        const QueryResult quarter = engine->query(pose);
        REQUIRE(at.flags == query_ok);
        QueryResult band_a, band_b;
        band_a.energy = half.energy - quarter.energy, band_b.energy = at.energy - half.energy;
        band_a.force = half.force - quarter.force, band_b.force = at.force - half.force;
        band_a.torque = half.torque - quarter.torque, band_b.torque = at.torque - half.torque;
        const ErrorEstimate expected = estimate_error(band_a, band_b);
        CAPTURE(scene.name);
        CAPTURE(c.name);
        CAPTURE(m);
        CAPTURE(pose.translation.transpose());
        // The kernel's bands start at the same modes up to the one mode of a conjugate
        // pair cut at m'/4 or m'/2, and float sums of the totals differ by ~1e-6 of them.
        CHECK(expected.energy > 0);
        CHECK(std::abs(at.error_estimate.energy - expected.energy) <=
              0.03 * expected.energy + 1e-5 * kErrorEstimateScale * std::abs(at.energy));
        if (c.variant.force) {
          CHECK(expected.force > 0);
          CHECK(std::abs(at.error_estimate.force - expected.force) <=
                0.03 * expected.force + 1e-5 * kErrorEstimateScale * at.force.norm());
        }
        if (c.variant.torque) {
          CHECK(expected.torque > 0);
          CHECK(std::abs(at.error_estimate.torque - expected.torque) <=
                0.03 * expected.torque + 1e-5 * kErrorEstimateScale * at.torque.norm());
        }
      }
    }
  }
}

Scene coarse(const std::string& file) {
  Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/" + file);
  if (scene.grid.spacing) *scene.grid.spacing *= 2;
  if (scene.grid.resolution) *scene.grid.resolution /= 2;
  return scene;
}

TEST_CASE("error estimate: the kernels' band sums equal the differences of queries at m'/4, m'/2 and m'") {
  {
    const Scene scene = coarse("default.json");
    const AssemblyPair pair = test::build_small_pair(scene);
    const double h = pair.spectra.spacing;
    const Pose assembled = trajectory_pose(scene.trajectory, scene.trajectory.keyframes.back().time_s);
    Pose contact = assembled;
    contact.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(3 * M_PI / 180, Vector3d::UnitX())) * contact.rotation;
    contact.translation += Vector3d(0.3 * h, 0, 0);
    Pose generic = assembled;
    generic.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(25 * M_PI / 180, Vector3d(1, 2, 3).normalized())) * generic.rotation;
    generic.translation += Vector3d(0.1 * h, -0.2 * h, 4 * h);
    QueryVariant tricubic = query_variant_for(scene, Interpolation::tricubic);
    QueryVariant every_mode = query_variant_for(scene, Interpolation::trilinear);
    every_mode.fold_conjugate_pairs = false;
    QueryVariant exact = tricubic;
    exact.rotation = RotationMethod::exact_product;
    exact.product_update = ProductUpdate::each_query;
    exact.product_modes = 16384;
    check_bands(scene, pair,
                {{"6-DOF tricubic, pairs folded", tricubic},
                 {"6-DOF trilinear, every mode", every_mode},
                 {"exact product", exact}},
                {contact, generic});
  }
  {
    const Scene scene = coarse("peg_hole_translation.json");
    REQUIRE(scene.motion == Motion::translation);
    const AssemblyPair pair = test::build_small_pair(scene);
    const double h = pair.spectra.spacing;
    const Pose end = trajectory_pose(scene.trajectory, scene.trajectory.keyframes.back().time_s);
    Pose side = end, above = end;
    side.translation += Vector3d(0.3 * h, 0.1 * h, 0);
    above.translation += Vector3d(-0.2 * h, 0, 3 * h);
    QueryVariant lines = query_variant_for(scene, Interpolation::trilinear);
    QueryVariant every_mode = lines;
    every_mode.fold_conjugate_pairs = false;
    check_bands(scene, pair,
                {{"translation lines, pairs folded", lines}, {"translation lines, every mode", every_mode}},
                {side, above});
  }
}

}  // namespace
}  // namespace snapfit
