// The region of part 1 a scene needs (pipeline/reach_region.h): its closed form for a
// straight slide, the crop and the fade on their own, and on a block much wider than the
// peg going into its hole, the energy, force, torque and contact with part 1 cut down to
// the region against the same with all of part 1: equal at every mode, and within the
// error estimates at the loop's m'. Out of the region the loop renders no engine wrench.
#include <doctest/doctest.h>
#include <cmath>
#include <string>
#include <vector>

#include "engine/query/query_engine.h"
#include "engine/query/reference_query.h"
#include "pipeline/assembly_pair.h"
#include "pipeline/reach_region.h"
#include "scheduler/haptics/rigid_contact.h"
#include "scheduler/haptics/scripted_device.h"
#include "scheduler/haptics/trajectory.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "snapfit/haptic_loop.h"
#include "tests/test_engine_support.h"

namespace snapfit {
namespace {

// A block 72 mm wide (a rod or plate far larger than the region in use) with one hole, a
// peg of radius 5 going in from 10 mm above, tilted 2 degrees at first.
constexpr const char* kWideBlock = R"({
  "snapfit_scene": 1, "name": "wide block, one hole", "units": "mm",
  "part1": {"name": "block", "procedural": {"type": "hole_block", "peg_radius": 5, "clearance": 0.2,
            "hole_depth": 12, "width": 72, "height": 16, "chamfer": 0.5, "segments": 48}},
  "part2": {"name": "peg", "procedural": {"type": "peg", "radius": 5, "length": 24, "chamfer": 0, "segments": 48},
            "pose": {"position": [0.5, 0, 10], "rotation": {"axis": [0, 1, 0], "angle_deg": 2}}},
  "assembled_pose": {"position": [0, 0, -12]},
  "descriptor": {"kind": "skeletal_density", "sigma": 0.5, "lambda_in": 3, "lambda_out": 1, "tolerance": 0.1},
  "grid": {"spacing": 1.2, "padding": 4},
  "outputs": ["energy", "force", "torque"], "motion": "6dof",
  "trajectory": {"keyframes": [
    {"time_s": 0, "position": [0.5, 0, 10], "rotation": {"axis": [0, 1, 0], "angle_deg": 2}},
    {"time_s": 1, "position": [0.2, 0, 1], "rotation": {"axis": [0, 1, 0], "angle_deg": 1}},
    {"time_s": 2, "position": [0, 0, -12]}]}
})";

Scene wide_block(const std::string& region) {
  Scene s = parse_scene(kWideBlock, "wide block");
  if (region == "whole") s.grid.region.kind = RegionKind::whole;
  return s;
}

PairOptions quiet() {
  PairOptions o;
  o.note = [](const std::string&) {};
  return o;
}

}  // namespace

TEST_CASE("reach region: a straight slide sweeps part 2's grid box along it, plus the margin") {
  Scene s = wide_block("reach");
  s.motion = Motion::translation;
  s.part2.pose = Pose{};
  s.part2.pose.translation = {0, 0, 10};
  s.trajectory.keyframes = {Keyframe{0, s.part2.pose}, Keyframe{1, Pose{}}};
  s.trajectory.keyframes[1].pose.translation = {0, 0, -20};
  s.grid.region.margin = 3.0;
  GridSpec g;
  g.origin = {-9, -9, -4};
  g.spacing = 1.2;
  g.dims = {16, 16, 27};
  const ReachRegion r = reach_region(s, g);
  REQUIRE(r.bounded);
  const Eigen::Vector3d lo = g.origin, hi = g.point(15, 15, 26);
  CHECK((r.box.min() - (lo + Eigen::Vector3d(-3, -3, -23))).norm() < 1e-9);
  CHECK((r.box.max() - (hi + Eigen::Vector3d(3, 3, 13))).norm() < 1e-9);
  // A declared workspace at any orientation: the ball about part 2's origin holding its box.
  s.motion = Motion::six_dof;
  s.grid.region.kind = RegionKind::workspace;
  s.grid.region.workspace_min = {-1, -2, -3};
  s.grid.region.workspace_max = {1, 2, 3};
  const ReachRegion w = reach_region(s, g);
  double reach = 0;
  for (int c = 0; c < 8; ++c) reach = std::max(reach, Eigen::AlignedBox3d(lo, hi).corner(Eigen::AlignedBox3d::CornerType(c)).norm());
  CHECK((w.box.min() - Eigen::Vector3d(-1 - reach - 3, -2 - reach - 3, -3 - reach - 3)).norm() < 1e-9);
  // No trajectory, or "whole": all of part 1.
  s.grid.region.kind = RegionKind::reach;
  s.trajectory.keyframes.clear();
  CHECK_FALSE(reach_region(s, g).bounded);
  s = wide_block("whole");
  CHECK_FALSE(reach_region(s, g).bounded);
}

TEST_CASE("reach region: the crop keeps the grid's own points, the fade is 1 inside and 0 a fade away") {
  GridSpec full;
  full.origin = {-10.3, -5, 0.25};
  full.spacing = 0.5;
  full.dims = {60, 30, 20};
  const Eigen::AlignedBox3d keep(Eigen::Vector3d(-2.1, -10, 3.0), Eigen::Vector3d(4.02, 2.0, 100));
  const GridSpec c = crop_grid(full, keep);
  // On the same lattice, inside the full grid, and covering the kept box (clipped to the grid).
  const Eigen::Vector3d steps = (c.origin - full.origin) / full.spacing;
  CHECK((steps - steps.array().round().matrix()).norm() < 1e-9);
  for (int a = 0; a < 3; ++a) {
    CHECK(c.origin[a] <= std::max(keep.min()[a], full.origin[a]) + 1e-12);
    CHECK(c.origin[a] + c.spacing * (c.dims[a] - 1) >=
          std::min(keep.max()[a], full.origin[a] + full.spacing * (full.dims[a] - 1)) - 1e-12);
    CHECK(c.origin[a] + c.spacing * (c.dims[a] - 1) < keep.max()[a] + full.spacing);
  }
  CHECK(c.count() < full.count());
  CHECK_THROWS_WITH(crop_grid(full, Eigen::AlignedBox3d(Eigen::Vector3d(50, 50, 50), Eigen::Vector3d(60, 60, 60))),
                    doctest::Contains("does not overlap"));

  std::vector<float> ones(full.count(), 1.0f);
  const Eigen::AlignedBox3d box(Eigen::Vector3d(-5, -5, -5), Eigen::Vector3d(5, 2, 5));
  fade_outside(full, box, 2.0, ones);
  for (std::size_t i = 0; i < ones.size(); ++i) {
    const double d = box.exteriorDistance(full.point(i));
    CAPTURE(d);
    if (d <= 0) CHECK(ones[i] == 1.0f);
    if (d >= 2) CHECK(ones[i] == 0.0f);
    if (d > 0 && d < 2) CHECK(ones[i] == doctest::Approx(0.5 * (1 + std::cos(M_PI * d / 2))).epsilon(1e-6));
  }
}

TEST_CASE("reach region: on a wide block, part 1 cut to the region gives the whole part's energy, force, torque and contact") {
  const test::CacheDirScope cache;
  const FftLibrary fft;
  const AssemblyPair region = build_assembly_pair(wide_block("reach"), test::test_context(), fft, quiet());
  const AssemblyPair whole = build_assembly_pair(wide_block("whole"), test::test_context(), fft, quiet());
  REQUIRE(region.region.bounded);
  REQUIRE_FALSE(whole.region.bounded);
  MESSAGE(region.region.reason);
  // Much less of part 1 to compute and transform.
  CHECK(2 * region.grids.part1.count() < whole.grids.part1.count());
  CHECK(region.spectra.part1.rho.size() < whole.spectra.part1.rho.size());

  // Every pose of the trajectory keeps part 2 inside the region; far to the side it does not.
  const Scene& scene = region.scene;
  for (int i = 0; i <= 200; ++i) CHECK(pose_in_region(region.region, trajectory_pose(scene.trajectory, 0.01 * i)));
  Pose aside;
  aside.translation = {30, 0, 2};
  CHECK_FALSE(pose_in_region(region.region, aside));

  // Every mode, R = I, translations that carry part 2's grid onto part 1's lattice: both
  // sums are the discrete correlation h^3 sum rho_1(x) rho_2(x - t), and the region's
  // rho_1 equals the whole part's wherever rho_2(x - t) is not zero.
  // The two sums round differently (single-precision spectra on FFT grids of different
  // sizes): they are compared on the scale of the largest energy, at the fit.
  const Eigen::Vector3d offset = region.grids.part1.origin - region.grids.part2.origin;
  const double h = region.grids.spacing;
  std::vector<std::pair<double, double>> energies;
  for (const Eigen::Vector3d& near : {Eigen::Vector3d(0, 0, -12), Eigen::Vector3d(0, 0, 8), Eigen::Vector3d(1, 0, 1),
                                      Eigen::Vector3d(0, 0, -6), Eigen::Vector3d(2, 1, 3)}) {
    Pose p;
    p.translation = offset + h * ((near - offset) / h).array().round().matrix();
    ReferenceOptions every;
    every.modes = 0;
    const QueryResult a = reference_query(region.spectra, p, every), b = reference_query(whole.spectra, p, every);
    REQUIRE(a.flags == query_ok);
    REQUIRE(b.flags == query_ok);
    energies.emplace_back(a.energy, b.energy);
  }
  const double scale = std::abs(energies.front().second);
  REQUIRE(scale > 0);
  for (const auto& [a, b] : energies) {
    CAPTURE(b);
    CHECK(std::abs(a - b) <= 1e-5 * scale);
  }

  // At the loop's m', along the trajectory (turned): equal within the two estimates.
  auto engine_r = make_query_engine(test::test_context(), region.spectra, query_variant_for(scene), test::test_program_cache());
  auto engine_w = make_query_engine(test::test_context(), whole.spectra, query_variant_for(scene), test::test_program_cache());
  engine_r->set_modes(65536);
  engine_w->set_modes(65536);
  double est_region = 0, est_whole = 0;
  for (int i = 0; i <= 8; ++i) {
    const Pose p = trajectory_pose(scene.trajectory, 0.25 * i);
    CAPTURE(p.translation.transpose());
    const QueryResult a = engine_r->query(p), b = engine_w->query(p);
    REQUIRE(a.flags == query_ok);
    REQUIRE(b.flags == query_ok);
    CHECK(std::abs(a.energy - b.energy) <= a.error_estimate.energy + b.error_estimate.energy);
    CHECK((a.force - b.force).norm() <= a.error_estimate.force + b.error_estimate.force);
    CHECK((a.torque - b.torque).norm() <= a.error_estimate.torque + b.error_estimate.torque);
    est_region += a.error_estimate.energy;
    est_whole += b.error_estimate.energy;
  }
  // The same m' spends its modes on the smaller region: a smaller estimate.
  MESSAGE("energy estimates summed along the trajectory at m' 65536: region " << est_region << ", whole " << est_whole);
  CHECK(est_region < est_whole);

  // The contact: part 1's geometry only where part 2 reaches, the same wrench there.
  const auto contact_r = rigid_contact_for(region.scene, region.part(1).mesh, region.part(2).mesh, h);
  const auto contact_w = rigid_contact_for(whole.scene, whole.part(1).mesh, whole.part(2).mesh, h);
  REQUIRE(contact_r);
  REQUIRE(contact_w);
  CHECK(contact_r->part1_distance.coarse_values.size() < contact_w->part1_distance.coarse_values.size());
  CHECK(contact_r->part1_samples.points.size() < contact_w->part1_samples.points.size());
  for (const Eigen::Vector3d& t : {Eigen::Vector3d(0.4, 0, -6), Eigen::Vector3d(0, 0.5, -11), Eigen::Vector3d(0.2, 0.3, -12.3)}) {
    Pose p;
    p.translation = t;
    p.rotation = Eigen::AngleAxisd(0.02, Eigen::Vector3d::UnitY());
    CAPTURE(t.transpose());
    const ContactWrench a = contact_wrench(*contact_r, p), b = contact_wrench(*contact_w, p);
    CHECK(b.points > 0);
    CHECK(a.points == b.points);
    CHECK((a.wrench.force - b.wrench.force).norm() <= 1e-9 + 1e-6 * b.wrench.force.norm());
  }
}

TEST_CASE("reach region: out of the region the loop renders none of the engine's wrench, and counts the frames") {
  struct Held : HapticDevice {
    BodyState state;
    BodyState read(double) override { return state; }
    void send(const Wrench&, double) override {}
    DeviceLimits limits() const override { return {}; }
  } device;
  WrenchEvaluator engine;
  engine.evaluate = [](const Pose&) {
    QueryResult r;
    r.force = Eigen::Vector3d(100, 0, 0);
    r.modes = 4096;
    return r;
  };
  engine.set_modes = [](std::size_t) {};
  LoopConfig c;
  c.duration_s = 0.1;
  c.coupling = make_coupling(1e-3, 0.05, 2e-6, 800, 0.05, 1.0);
  c.geometry_gain = 0.01;
  c.modes.levels = {4096};
  for (bool inside : {true, false}) {
    c.in_region = [inside](const Pose&) { return inside; };
    const LoopReport r = run_haptic_loop(device, engine, c, simulated_loop_clock(), device.state);
    REQUIRE(!r.log.empty());
    CHECK(r.out_of_region_frames == (inside ? 0 : r.frames));
    CHECK(r.log.back().geometric.force.x() == doctest::Approx(inside ? 1.0 : 0.0));
  }
}

}  // namespace snapfit
