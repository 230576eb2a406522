// Voxmap PointShell (scheduler/vps/voxmap.h, scheduler/vps/vps_method.h): the voxmap of a box against
// its closed-form voxel counts, one point against a plane against the closed-form force
// and torque, and a cube inserted into a square cup through the haptic loop: it goes in
// at a clearance of twice the voxel size and jams at zero clearance (seed 002 8.2.1);
// `snapfit run` with a vps scene; the loop's speed limit.
#include <doctest/doctest.h>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scheduler/haptics/assembly_session.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/scripted_device.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "scheduler/vps/voxmap.h"
#include "scheduler/vps/vps_method.h"
#include "tests/test_meshes.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("vps: the voxmap of a box has the closed-form surface, interior and proximity counts") {
  // Box of side 4 at voxel 0.5: the faces lie on voxel centre planes, so the surface
  // layer is the 9^3 lattice's shell, the interior its 7^3 core, and two proximity
  // layers add 13^3 - 9^3 voxels.
  const Mesh box = test::box_mesh(Eigen::Vector3d(-2, -2, -2), Eigen::Vector3d(2, 2, 2));
  const Voxmap m = build_voxmap(box, 0.5, 2);
  CHECK(m.count(VoxelState::surface) == 9 * 9 * 9 - 7 * 7 * 7);
  CHECK(m.count(VoxelState::interior) == 7 * 7 * 7);
  CHECK(m.count(VoxelState::proximity) == 13 * 13 * 13 - 9 * 9 * 9);
  Eigen::Vector3i centre;
  REQUIRE(m.locate(Eigen::Vector3d::Zero(), centre));
  CHECK(m.state[m.index(centre.x(), centre.y(), centre.z())] == VoxelState::interior);
  CHECK(m.layer[m.index(centre.x(), centre.y(), centre.z())] == 4);
  CHECK_THROWS_WITH(build_voxmap(Mesh{}, 0.5, 2), "voxmap: the mesh is empty");
  CHECK_THROWS_WITH(build_voxmap(box, -1, 2), doctest::Contains("voxel size must be > 0"));
}

TEST_CASE("vps: the point shell lies on the surface with inward unit normals") {
  const Mesh peg = test::peg_mesh(1, 3);
  const PointShell shell = build_point_shell(peg, 0.2);
  CHECK(shell.points.size() > 100);
  for (std::size_t i = 0; i < shell.points.size(); ++i) {
    const Eigen::Vector3d& p = shell.points[i];
    const double side = std::hypot(p.x(), p.y());
    // On the side wall (between the 64-gon's apothem and its radius) or on a cap.
    const bool on_side = side >= std::cos(M_PI / 64) - 1e-9 && side <= 1 + 1e-9;
    const bool on_cap = std::abs(p.z()) < 1e-9 || std::abs(p.z() - 3) < 1e-9;
    CHECK((on_side || on_cap));
    CHECK(shell.normals[i].norm() == doctest::Approx(1));
    // Inward: the peg is convex, so its centre lies on the inner side of every face.
    CHECK(shell.normals[i].dot(Eigen::Vector3d(0, 0, 1.5) - p) > 0);
  }
}

TEST_CASE("vps: one point against a plane gives the closed-form force and torque") {
  // Part 1 fills z < 0 (a box whose top face z = 0 is a voxel centre plane, its other
  // faces farther from the point than the top); the point's normal is +z, so its depth
  // below the tangent plane plus its voxel's interior layers is -z at every depth.
  const double voxel = 0.5;
  const Mesh slab = test::box_mesh(Eigen::Vector3d(-8, -8, -8), Eigen::Vector3d(8, 8, 0));
  VpsModel model;
  model.voxmap = build_voxmap(slab, voxel, 2);
  model.shell.points = {Eigen::Vector3d(1.0, 0.4, 0)};
  model.shell.normals = {Eigen::Vector3d::UnitZ()};
  model.shell.chunks = {ShellChunk{model.shell.points[0], 0, 0, 1}};
  model.stiffness = 700;
  model.braking = 3;
  model.metres_per_unit = 1e-3;
  model.mass_kg = 1e3;  // large: the braking bound does not act
  model.inertia_kg_m2 = 1e3;
  BodyState part;
  part.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  const Eigen::Vector3d r = part.pose.rotation * model.shell.points[0];
  for (double depth : {0.05, 0.2, 0.6, 1.3, 2.4}) {
    CAPTURE(depth);
    part.pose.translation = Eigen::Vector3d(0.1, 0.2, -depth);
    const VpsResult v = vps_wrench(model, part);
    const Eigen::Vector3d force = Eigen::Vector3d(0, 0, 700 * 1e-3 * depth);
    CHECK(v.contacts == 1);
    CHECK((v.query.force - force).norm() < 1e-12);
    CHECK((v.query.torque - r.cross(force)).norm() < 1e-12);
    CHECK(v.query.energy == doctest::Approx(0.5 * 700 * 1e-3 * depth * depth));
  }
  // Above the plane, in the first proximity layer: no force at rest; approaching, the
  // braking force -b (v.n) n (seed 002 eq. 5); receding, none.
  part.pose.translation = Eigen::Vector3d(0.1, 0.2, 0.45);
  CHECK(vps_wrench(model, part).query.force.norm() == 0);
  part.velocity = Eigen::Vector3d(3, 0, -40);  // scene units / s
  const VpsResult braking = vps_wrench(model, part);
  CHECK(braking.braking_points == 1);
  CHECK((braking.query.force - Eigen::Vector3d(0, 0, 3 * 1e-3 * 40)).norm() < 1e-12);
  CHECK((braking.query.torque - r.cross(braking.query.force)).norm() < 1e-12);
  part.velocity = Eigen::Vector3d(0, 0, 40);
  CHECK(vps_wrench(model, part).query.force.norm() == 0);
  // Two layers up is free space.
  part.pose.translation.z() = 1.6;
  part.velocity = Eigen::Vector3d(0, 0, -40);
  CHECK(vps_wrench(model, part).braking_points == 0);
}

namespace {

// A cube of side 2 b (b = inner - clearance) above a cup whose square cavity has
// half-width `inner` (its walls between voxel centres, as a part would be in general),
// played down into it through the loop in simulated time; the device's target ends half
// a voxel off centre, 3 units deep (the cavity is 4 deep).
SessionResult insert_cube(double voxel, double clearance) {
  const double inner = 2.1, b = inner - clearance;
  Scene scene;
  scene.name = "cube in a cup";
  scene.assembled_pose = Pose{};
  scene.assembled_pose->translation = Eigen::Vector3d(0, 0, -3);
  const Mesh cup = test::cup_mesh(6, inner, 4, 6);
  const Mesh cube = test::box_mesh(Eigen::Vector3d(-b, -b, 0), Eigen::Vector3d(b, b, 2 * b));
  Keyframe start, end;
  start.pose.translation = Eigen::Vector3d(0.5 * voxel, 0, 1);
  end.time_s = 2;
  end.pose.translation = Eigen::Vector3d(0.5 * voxel, 0, -3);
  scene.trajectory.keyframes = {start, end};
  scene.haptics.settle_s = 1;
  scene.haptics.success_position = voxel;
  scene.vps.voxel_size = voxel;
  const CouplingParams coupling = coupling_for(scene, cube);
  const VpsModel model = vps_model_for(scene, cup, cube, voxel, coupling);
  SessionOptions options;
  options.simulated_time = true;
  return run_scripted_session(scene, cube, voxel, vps_loop_config(scene, model, coupling), vps_evaluator(model),
                              options);
}

}  // namespace

TEST_CASE("vps: a cube goes into a cup at twice the voxel size of clearance and jams at zero") {
  const double voxel = 0.25;
  const SessionResult loose = insert_cube(voxel, 2 * voxel);
  INFO("clearance 2 voxels: final error ", loose.final_error.position, ", z ",
       loose.loop.final_part.pose.translation.z());
  CHECK(loose.assembled);
  const SessionResult tight = insert_cube(voxel, 0);
  INFO("clearance 0: final z ", tight.loop.final_part.pose.translation.z());
  CHECK(!tight.assembled);
  CHECK(tight.loop.final_part.pose.translation.z() > -3 + 4 * voxel);  // jammed well short of the target
  // The jammed cube rests on the rim: the user feels the coupling's reaction, upwards.
  CHECK(tight.loop.log.back().sent.force.z() > 0.5);
}

TEST_CASE("vps: snapfit run plays a vps scene and names the method in summary.json") {
  // The shipped 0.5 mm clearance scene with "method": "vps" at a quarter-millimetre voxel.
  nlohmann::json scene;
  std::ifstream(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/peg_hole_clearance_0p5.json") >> scene;
  scene["method"] = "vps";
  scene["vps"] = {{"voxel_size", 0.25}};
  const test::TempDir dir;
  test::write_text(dir.file("vps.json"), scene.dump());
  const test::Command run = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("vps.json") +
                                              " --simulated-time --out " + dir.file("out"));
  INFO(run.output);
  REQUIRE(run.status == 0);
  nlohmann::json summary;
  std::ifstream(dir.file("out/summary.json")) >> summary;
  CHECK(summary["method"] == "vps");
  CHECK(summary["vps"]["voxel_size"] == 0.25);
  CHECK(summary["vps"]["shell_points"].get<int>() > 1000);
  CHECK(summary["tuning"].is_null());
  CHECK(summary["haptic_loop"]["frames"] == 5500);
  CHECK(summary["haptic_loop"]["assembled"] == true);  // 0.5 mm of clearance, twice the voxel size
  // The plan printed and written is Voxmap PointShell's, not snapfit's.
  const std::string plan = summary["plan"].dump();
  CHECK(plan.find("Voxmap PointShell") != std::string::npos);
  CHECK(plan.find("voxel 0.25 mm") != std::string::npos);
  CHECK(plan.find("skeletal density") == std::string::npos);
  CHECK(plan.find("tricubic") == std::string::npos);
  CHECK(run.output.find("sigma") == std::string::npos);
  // A bad vps field stops the run with the field named.
  scene["vps"]["voxel_size"] = 0;
  test::write_text(dir.file("bad.json"), scene.dump());
  const test::Command bad = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("bad.json"));
  CHECK(bad.status != 0);
  CHECK(bad.output.find("vps.voxel_size: must be > 0 (got 0)") != std::string::npos);
}

TEST_CASE("vps: the loop's speed limit bounds each step's travel and turn") {
  // The device holds part 2 10 units away and turned 0.5 rad: the coupling alone would move
  // the part ~0.16 units in the first step; the limit allows 0.01 units and 0.002 rad.
  Keyframe target;
  target.pose.translation = Eigen::Vector3d(10, 0, 0);
  target.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()));
  ScriptedDevice device(Trajectory{{target}}, DeviceLimits{});
  LoopConfig config;
  config.duration_s = 0.1;
  config.coupling = make_coupling(1e-3, 0.05, 1e-5, 800, 0.08, 1);
  config.modes.levels = {1};
  config.max_travel = 0.01;
  config.max_rotation = 0.002;
  WrenchEvaluator none;
  none.evaluate = [](const Pose&) { return QueryResult{}; };
  const LoopReport report = run_haptic_loop(device, none, config, simulated_loop_clock(), BodyState{});
  REQUIRE(report.log.size() == 100);
  for (std::size_t i = 1; i < report.log.size(); ++i) {
    const Pose& a = report.log[i - 1].part;
    const Pose& b = report.log[i].part;
    CHECK((b.translation - a.translation).norm() <= 0.01 + 1e-12);
    CHECK(rotation_between(a.rotation, b.rotation).norm() <= 0.002 + 1e-12);
  }
  // Far from the target the whole time, it moved at the limit every step.
  CHECK(report.final_part.pose.translation.x() == doctest::Approx(100 * 0.01));
  CHECK(rotation_between(Eigen::Quaterniond::Identity(), report.final_part.pose.rotation).norm() ==
        doctest::Approx(100 * 0.002));
}
