// The wrench the loop renders from seed 000's energy at the smallest m' of the ladder,
// on a part much larger than the region in use (a wide plate with one hole, the peg
// above it and away from it, never touching): what the per-query error estimate vouches
// for (scheduler/haptics/wrench_trust.h) is either within the tolerance of the exact wrench
// (every mode, double precision, reference_query) or never pushes against it and is
// never stronger than it. Without the trust the same truncated wrench does push against
// the exact one at some of these poses: the spurious push the trust removes.
#include <doctest/doctest.h>
#include <string>
#include <vector>

#include "engine/query/query_engine.h"
#include "engine/query/reference_query.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/wrench_trust.h"
#include "tests/test_engine_support.h"

namespace snapfit {
namespace {

// A 60 x 60 mm plate 16 mm thick with one hole, a peg of radius 5 above it.
constexpr const char* kPlateScene = R"({
  "snapfit_scene": 1, "name": "wide plate, one hole", "units": "mm",
  "part1": {"name": "plate", "procedural": {"type": "hole_block", "peg_radius": 5, "clearance": 0.2,
            "hole_depth": 12, "width": 60, "height": 16, "chamfer": 0.5, "segments": 48}},
  "part2": {"name": "peg", "procedural": {"type": "peg", "radius": 5, "length": 24, "chamfer": 0, "segments": 48},
            "pose": {"position": [0, 0, 8]}},
  "assembled_pose": {"position": [0, 0, -12]},
  "descriptor": {"kind": "skeletal_density", "sigma": 0.5, "lambda_in": 3, "lambda_out": 1, "tolerance": 0.1},
  "grid": {"spacing": 1.2, "padding": 4},
  "outputs": ["energy", "force", "torque"], "motion": "6dof"
})";

constexpr std::size_t kSmallestModes = 512;  // ModeTuningOptions::min_modes
constexpr std::size_t kLargerModes = 65536;

struct Rendered {
  Eigen::Vector3d force, torque;  // N, N m
};

// Accurate (within max(relative |exact|, floor)), or conservative (not against the exact
// one and not stronger than it, up to the floor).
bool vouchable(const Eigen::Vector3d& rendered, const Eigen::Vector3d& exact, double relative, double floor) {
  if ((rendered - exact).norm() <= std::max(relative * exact.norm(), floor)) return true;
  return rendered.dot(exact) >= 0 && rendered.norm() <= exact.norm() + floor;
}

}  // namespace

TEST_CASE("vouched wrench: on a wide plate at the smallest m', away from contact, no push or twist against the exact") {
  const test::CacheDirScope cache;
  const Scene scene = parse_scene(kPlateScene, "test plate scene");
  const FftLibrary fft;
  PairOptions options;
  options.note = [](const std::string&) {};
  const AssemblyPair pair = build_assembly_pair(scene, test::test_context(), fft, options);
  auto engine = make_query_engine(test::test_context(), pair.spectra, query_variant_for(scene, Interpolation::tricubic),
                                  test::test_program_cache());

  // Aligned poses (R = I puts every rotated frequency on a node, so every mode in double
  // is the exact energy): the peg's tip 1.5 to 10 mm above the plate, over the hole, at
  // its rim and over the plate's face, never touching.
  std::vector<Pose> poses;
  for (double z : {1.5, 3.0, 5.0, 7.5, 10.0})
    for (double x : {0.0, 2.5, 6.0, 14.0, 22.0}) {
      Pose p;
      p.translation = {x, 0.4 * x, z};
      poses.push_back(p);
    }
  std::vector<QueryResult> exact;
  for (const Pose& p : poses) {
    ReferenceOptions every;
    every.modes = 0;
    exact.push_back(reference_query(pair.spectra, p, every));
    REQUIRE(exact.back().flags == query_ok);
  }
  // The loop's gain: the largest exact force over these poses is rendered as 1 N.
  double largest = 0;
  for (const QueryResult& r : exact) largest = std::max(largest, r.force.norm());
  REQUIRE(largest > 0);
  const double gain = 1.0 / largest, u = 1e-3;
  const WrenchTrust trust;

  // At the smallest m' and at one the estimate vouches for more of.
  int withheld_at[2] = {0, 0};
  for (int level = 0; level < 2; ++level) {
    const std::size_t modes = level == 0 ? kSmallestModes : kLargerModes;
    engine->set_modes(modes);
    int raw_wrong = 0, vouched_wrong = 0, withheld = 0;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      CAPTURE(modes);
      CAPTURE(poses[i].translation.transpose());
      const QueryResult q = engine->query(poses[i]);
      REQUIRE(q.flags == query_ok);
      const Wrench raw{gain * q.force, gain * u * q.torque};
      const ErrorEstimate error{q.error_estimate.energy, gain * q.error_estimate.force,
                                gain * u * q.error_estimate.torque};
      const double w = wrench_trust(raw, error, trust);
      const Eigen::Vector3d exact_force = gain * exact[i].force, exact_torque = gain * u * exact[i].torque;
      const bool raw_ok = vouchable(raw.force, exact_force, trust.relative, trust.force_n) &&
                          vouchable(raw.torque, exact_torque, trust.relative, trust.torque_nm);
      const bool ok = vouchable(w * raw.force, exact_force, trust.relative, trust.force_n) &&
                      vouchable(w * raw.torque, exact_torque, trust.relative, trust.torque_nm);
      raw_wrong += !raw_ok;
      vouched_wrong += !ok;
      withheld += w == 0;
      CHECK(ok);
    }
    MESSAGE("m' " << modes << ", " << poses.size() << " poses: the raw wrench wrong at " << raw_wrong
                  << ", the vouched one at " << vouched_wrong << ", withheld at " << withheld);
    CHECK(vouched_wrong == 0);
    if (level == 0) CHECK(raw_wrong > 0);  // a hard case: without the trust the wrench is wrong here
    withheld_at[level] = withheld;
  }
  // More modes, a smaller estimate: more of the wrench is rendered.
  CHECK(withheld_at[1] < withheld_at[0]);
}

}  // namespace snapfit
