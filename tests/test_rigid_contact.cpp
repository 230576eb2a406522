// Rigid contact (mesh/signed_distance_grid.h, mesh/contact_samples.h,
// scheduler/haptics/rigid_contact.h) on the shipped peg and hole: the distance grid against the
// exact point-to-mesh signed distance, the wrench against central differences of the
// contact energy, its stiffness against differences of the wrench, nothing at an exact
// zero-clearance fit; and with the engine, the rendered potential's rest point at the fit
// of every shipped peg-and-hole and three-peg scene.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <random>

#include "engine/query/query_engine.h"
#include "mesh/mesh_distance.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/modes/mode_tuning.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/parallel_contact.h"
#include "scheduler/haptics/rendered_wrench.h"
#include "scheduler/haptics/rigid_contact.h"
#include "tests/shipped_engine.h"
#include "scheduler/haptics/scripted_device.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "tests/allocation_count.h"

using namespace snapfit;

namespace {

struct ShippedPair {
  Scene scene;
  AssemblyPair pair;
};

const ShippedPair& default_pair() {
  static const ShippedPair p = [] {
    ShippedPair s;
    s.scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
    s.pair = prepare_assembly_pair(s.scene);
    return s;
  }();
  return p;
}

const RigidContactModel& default_contact() {
  static const std::shared_ptr<const RigidContactModel> m = [] {
    const ShippedPair& p = default_pair();
    const auto start = std::chrono::steady_clock::now();
    auto model = rigid_contact_for(p.scene, p.pair.part(1).mesh, p.pair.part(2).mesh, p.pair.grids.spacing);
    MESSAGE("contact model of scenes/default.json built in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s: "
            << model->part1_distance.bricks() << " + " << model->part2_distance.bricks() << " fine bricks, "
            << model->part1_samples.points.size() << " edge points of part 1, "
            << model->part2_samples.face_points << " face + " << model->part2_samples.feature_points
            << " edge points of part 2");
    return model;
  }();
  return *m;
}

Pose at(double x, double y, double z, const Eigen::Vector3d& axis = Eigen::Vector3d::UnitY(), double deg = 0) {
  Pose p;
  p.translation = Eigen::Vector3d(x, y, z);
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(deg * M_PI / 180, axis.normalized()));
  return p;
}

// The pose moved by dt (scene units) and turned by the left increment exp(dtheta).
Pose moved(const Pose& p, const Eigen::Vector3d& dt, const Eigen::Vector3d& dtheta) {
  Pose q = p;
  q.translation += dt;
  q.rotation = (rotation_exp(dtheta) * p.rotation).normalized();
  return q;
}

}  // namespace

TEST_CASE("rigid contact: each brick node holds its exact distance to half a brick step, a cell without one its side") {
  const ShippedPair& p = default_pair();
  const RigidContactModel& m = default_contact();
  for (int part = 1; part <= 2; ++part) {
    const SignedDistanceGrid& g = part == 1 ? m.part1_distance : m.part2_distance;
    const MeshDistanceIndex exact(p.pair.part(part).mesh);
    CHECK(g.brick_step == doctest::Approx(g.fine_spacing() / kBrickStepsPerSpacing));
    CHECK(reinterpret_cast<std::uintptr_t>(g.brick_values.data()) % 64 == 0);  // a brick: whole cache lines
    const std::size_t cx = g.dims.x() - 1, cy = g.dims.y() - 1, side = g.refine + 1;
    double worst = 0;
    std::size_t nodes = 0, outside = 0, inside = 0;
    for (std::size_t cell = 0; cell < g.brick_of_cell.size(); cell += 7) {
      const Eigen::Vector3d corner =
          g.origin + g.coarse * Eigen::Vector3d(double(cell % cx), double(cell / cx % cy), double(cell / (cx * cy)));
      const std::int32_t brick = g.brick_of_cell[cell];
      if (brick < 0) {  // the whole cell beyond the band, on the side its code says
        const double d = exact.signed_distance(corner + 0.5 * g.coarse * Eigen::Vector3d::Ones());
        CHECK(std::abs(d) > g.band);
        CHECK((d > 0) == (brick == kCoarseOutside));
        ++(brick == kCoarseOutside ? outside : inside);
        continue;
      }
      for (std::size_t n = 0; n < g.brick_nodes(); n += 5, ++nodes) {
        const Eigen::Vector3d node(double(n % side), double(n / side % side), double(n / (side * side)));
        const Eigen::Vector3d at = corner + g.fine_spacing() * node;
        const double stored = g.brick_values[std::size_t(brick) * g.brick_nodes() + n] * g.brick_step;
        worst = std::max(worst, std::abs(stored - exact.signed_distance(at)));
      }
    }
    MESSAGE("part " << part << ": " << nodes << " brick nodes, largest |stored - exact| " << worst << " (brick step "
                    << g.brick_step << "); " << outside << " cells outside, " << inside << " inside without a brick");
    CHECK(nodes > 0);
    CHECK(outside > 0);
    CHECK(worst <= 0.5 * g.brick_step * (1 + 1e-6));
  }
}

TEST_CASE("rigid contact: the distance grid matches the exact signed distance near the shipped parts") {
  const ShippedPair& p = default_pair();
  const RigidContactModel& m = default_contact();
  for (int part = 1; part <= 2; ++part) {
    const Mesh& mesh = p.pair.part(part).mesh;
    const SignedDistanceGrid& g = part == 1 ? m.part1_distance : m.part2_distance;
    const MeshDistanceIndex exact(mesh);
    std::mt19937 rng(7);
    std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles.size() - 1);
    std::uniform_real_distribution<double> unit(0, 1), offset(-g.band, g.band);
    double worst = 0, worst_flat = 0;
    int counted = 0;
    for (int i = 0; i < 4000; ++i) {
      // A point on a random triangle, moved off the surface along its normal.
      const Eigen::Vector3i t = mesh.triangles[pick(rng)];
      double a = unit(rng), b = unit(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      const Eigen::Vector3d &v0 = mesh.vertices[t[0]], &v1 = mesh.vertices[t[1]], &v2 = mesh.vertices[t[2]];
      const Eigen::Vector3d n = (v1 - v0).cross(v2 - v0).normalized();
      const Eigen::Vector3d q = v0 + a * (v1 - v0) + b * (v2 - v0) + offset(rng) * n;
      const double reference = exact.signed_distance(q);
      const double sampled = sample_signed_distance(g, q, nullptr);
      worst = std::max(worst, std::abs(sampled - reference));
      ++counted;
    }
    // Trilinear interpolation of a 1-Lipschitz function errs by at most half a fine
    // cell's diagonal; where the distance is smooth (flat and cylindrical walls) by far less.
    MESSAGE("part " << part << ": largest |grid - exact| " << worst << " over " << counted << " points within "
                    << g.band << " of the surface (fine spacing " << g.fine_spacing() << ")");
    CHECK(worst <= 0.5 * std::sqrt(3.0) * g.fine_spacing());
    (void)worst_flat;
  }
}

TEST_CASE("rigid contact: nothing at the exact zero-clearance fit, a stiff push back just past it") {
  const ShippedPair& p = default_pair();
  const RigidContactModel& m = default_contact();
  const Pose fit = *p.scene.assembled_pose;
  const ContactWrench at_fit = contact_wrench(m, fit);
  // 0.1 mm past the skin into the floor and into the wall.
  const double past = m.skin + 0.1;
  const ContactWrench deeper = contact_wrench(m, moved(fit, Eigen::Vector3d(0, 0, -past), Eigen::Vector3d::Zero()));
  const ContactWrench aside = contact_wrench(m, moved(fit, Eigen::Vector3d(past, 0, 0), Eigen::Vector3d::Zero()));
  MESSAGE("at the fit: " << at_fit.points << " points, |F| " << at_fit.wrench.force.norm() << " N, depth "
                         << at_fit.depth << "; skin " << m.skin << "; " << past << " into the floor: "
                         << deeper.wrench.force.transpose() << " N; " << past
                         << " into the wall: " << aside.wrench.force.transpose() << " N");
  // The surfaces only touch at the fit: what remains is the tessellations' and the
  // grid's round-off, a small fraction of the push 0.1 mm further.
  CHECK(at_fit.wrench.force.norm() <= 0.01 * deeper.wrench.force.norm());
  // The floor's area (pi 5^2 mm^2) times k times 0.1 mm, within the sampling's error.
  const double floor_force = M_PI * 25 * p.scene.haptics.contact_stiffness_n_per_mm3 * 0.1;
  CHECK(deeper.wrench.force.z() == doctest::Approx(floor_force).epsilon(0.2));
  CHECK(aside.wrench.force.x() < -floor_force);  // half the wall pushes part 2 back to the axis
  const auto start = std::chrono::steady_clock::now();
  const int reps = 200;
  std::size_t points = 0;
  for (int i = 0; i < reps; ++i)
    points += contact_wrench(m, moved(fit, Eigen::Vector3d(0.01 * (i % 7), 0, 0.2), Eigen::Vector3d::Zero())).points;
  MESSAGE("contact_wrench at the fit: "
          << 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / reps
          << " ms per call (" << points / reps << " points in contact)");
}

TEST_CASE("rigid contact: the wrench is minus the gradient of the contact energy (shipped peg and hole)") {
  const ShippedPair& p = default_pair();
  const RigidContactModel& m = default_contact();
  const double u = m.metres_per_unit;
  const Pose fit = *p.scene.assembled_pose;
  // Into the floor, tilted against the wall, cutting the rim at the entry, and generic.
  const std::vector<Pose> poses = {moved(fit, Eigen::Vector3d(0.05, -0.02, -0.15), Eigen::Vector3d::Zero()),
                                   moved(fit, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.004, -0.002, 0)),
                                   at(0.35, 0.2, -1.2, Eigen::Vector3d(1, 1, 0), 1.5),
                                   at(-0.25, 0.3, -8, Eigen::Vector3d(0.3, 1, 0), 0.8)};
  for (const Pose& pose : poses) {
    const ContactWrench c = contact_wrench(m, pose);
    REQUIRE(c.points > 0);
    const double h = 1e-5;  // scene units and radians
    Eigen::Vector3d force_fd, torque_fd;
    for (int a = 0; a < 3; ++a) {
      const Eigen::Vector3d e = Eigen::Vector3d::Unit(a);
      force_fd[a] = -(contact_wrench(m, moved(pose, h * e, Eigen::Vector3d::Zero())).energy_j -
                      contact_wrench(m, moved(pose, -h * e, Eigen::Vector3d::Zero())).energy_j) /
                    (2 * h * u);
      torque_fd[a] = -(contact_wrench(m, moved(pose, Eigen::Vector3d::Zero(), h * e)).energy_j -
                       contact_wrench(m, moved(pose, Eigen::Vector3d::Zero(), -h * e)).energy_j) /
                     (2 * h);
    }
    MESSAGE(c.points << " points, depth " << c.depth << ": F " << c.wrench.force.transpose() << " (differences "
                     << force_fd.transpose() << "), T " << c.wrench.torque.transpose() << " (differences "
                     << torque_fd.transpose() << ")");
    CHECK((c.wrench.force - force_fd).norm() <= 2e-3 * c.wrench.force.norm() + 1e-9);
    CHECK((c.wrench.torque - torque_fd).norm() <= 2e-3 * c.wrench.torque.norm() + 1e-12);
  }
}

// The rest point: descending the potential the loop renders (seed 000's energy times the
// gain, plus the contact) from the assembled pose stays at the fit. Without the contact
// the same descent sinks below the blind hole's floor, where the truncated energy is lowest.
TEST_CASE("rigid contact: evaluated on several threads it equals the single-threaded sum") {
  // Shared models: a copy per thread count, helpers woken frame after frame.
  const RigidContactModel& m = default_contact();
  const auto model = std::make_shared<const RigidContactModel>(m);
  // Above the zero-clearance fit (nothing), tilted into the rim and wall, and free.
  const std::vector<Pose> poses = {at(0, 0, -19.9), at(0.1, -0.05, -19.8, Eigen::Vector3d(1, 1, 0), 0.4),
                                   at(0.3, 0, -15, Eigen::Vector3d::UnitX(), 1.0), at(0, 0, 5)};
  for (unsigned threads : {2u, 3u, 5u}) {
    const auto evaluate = contact_evaluator(model, threads);
    for (int round = 0; round < 3; ++round)
      for (const Pose& pose : poses) {
        const ContactWrench one = contact_wrench(m, pose), many = evaluate(pose);
        CAPTURE(threads);
        CAPTURE(pose.translation.transpose());
        CHECK(many.points == one.points);
        CHECK(many.depth == one.depth);
        CHECK(many.energy_j == doctest::Approx(one.energy_j).epsilon(1e-12));
        CHECK((many.wrench.force - one.wrench.force).norm() <= 1e-12 * (1 + one.wrench.force.norm()));
        CHECK((many.wrench.torque - one.wrench.torque).norm() <= 1e-12 * (1 + one.wrench.torque.norm()));
        CHECK((many.stiffness - one.stiffness).norm() <= 1e-12 * (1 + one.stiffness.norm()));
        CHECK(many.stiffness.isApprox(many.stiffness.transpose()));
      }
  }
  CHECK(contact_wrench(m, poses[1]).points > 100);  // tilted and lowered into the rim and the wall
  CHECK(contact_wrench(m, poses[2]).points > 100);
  CHECK(contact_threads_for(m, 1) == 1);
}

TEST_CASE("rigid contact: no heap allocation per evaluation, on one thread and on several") {
  const auto model = std::make_shared<const RigidContactModel>(default_contact());
  const Pose fit = *default_pair().scene.assembled_pose;
  const std::vector<Pose> poses = {fit, moved(fit, Eigen::Vector3d(0.2, 0, -0.1), Eigen::Vector3d::Zero()),
                                   moved(fit, Eigen::Vector3d(0, 0, -2.5), Eigen::Vector3d(0.01, 0, 0)),
                                   at(0.3, 0, -15, Eigen::Vector3d::UnitX(), 1.0)};
  for (unsigned threads : {1u, 2u}) {
    CAPTURE(threads);
    const auto evaluate = contact_evaluator(model, threads);
    std::size_t touching = 0;
    for (const Pose& pose : poses) touching += evaluate(pose).points;  // helpers started
    long allocations = 0;
    {
      test::CountAllocations count;
      for (int round = 0; round < 50; ++round)
        for (const Pose& pose : poses) touching += evaluate(pose).points;
      allocations = count.count();
    }
    CHECK(allocations == 0);
    CHECK(touching > 0);
  }
}

TEST_CASE("rigid contact: the rendered potential rests at the fit of the shipped scenes (m' 8192)") {
  for (const char* file : {"default.json", "peg_hole_clearance_0p5.json", "three_pegs.json"}) {
    const Scene scene = test::shipped_scene(file);
    const test::ShippedEngine shipped = test::shipped_engine(scene);
    const AssemblyPair& pair = shipped.pair;
    QueryEngine* engine = shipped.engine.get();
    const TuningResult fixed = pick_modes({TimingPoint{8192, 0, 0, 0, 1}}, scene.frame_budget_ms, 0.25);
    const auto contact = rigid_contact_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.spectra.spacing);
    REQUIRE(contact);
    double force_scale = 0;
    const LoopConfig config =
        loop_config_for(scene, pair.part(2).mesh, pair.spectra.spacing, *engine, fixed, force_scale, contact);
    const Pose fit = *scene.assembled_pose;
    const RestPoint rest =
        descend_rendered(wrench_evaluator(*engine), config.geometry_gain, config.contact, config.coupling, fit);
    const RestPoint soft =
        descend_rendered(wrench_evaluator(*engine), config.geometry_gain, nullptr, config.coupling, fit);
    const PoseError e = pose_error(rest.pose, fit), e_soft = pose_error(soft.pose, fit);
    MESSAGE(std::string(file) << ": rest point " << (rest.pose.translation - fit.translation).transpose() << " ("
                 << e.position << " mm, " << e.angle_deg << " deg, " << rest.steps
                 << " steps); without the contact " << (soft.pose.translation - fit.translation).transpose() << " ("
                 << e_soft.position << " mm, " << e_soft.angle_deg << " deg)");
    CHECK(e.position <= 0.1);
    CHECK(e.angle_deg <= 0.2);
  }
}

// A hand that drives the peg 3 mm through the blind hole's floor and holds it there: the
// contact, 1,000 times stiffer than the coupling, stays stable in the loop (implicit), the
// part stops at the floor within the skin plus the coupling's pull over the contact's
// stiffness, and comes to rest; the device feels the coupling stretched by the 3 mm.
TEST_CASE("rigid contact: a hand pushing through the floor is held at it, stably, in the loop") {
  const ShippedPair& p = default_pair();
  const auto model = std::shared_ptr<const RigidContactModel>(&default_contact(), [](const RigidContactModel*) {});
  const Pose fit = *p.scene.assembled_pose;
  Keyframe start{0.0, moved(fit, Eigen::Vector3d(0, 0, 1), Eigen::Vector3d::Zero())};
  Keyframe push{0.5, moved(fit, Eigen::Vector3d(0, 0, -3), Eigen::Vector3d::Zero())};
  Keyframe hold{2.0, push.pose};
  ScriptedDevice device(Trajectory{{start, push, hold}}, DeviceLimits{});
  LoopConfig config;
  config.duration_s = 2.0;
  config.coupling = make_coupling(1e-3, 0.05, 1e-5, 800, 0.08, 1.0);
  config.modes.levels = {1};
  config.contact = contact_evaluator(model);
  WrenchEvaluator none;
  none.evaluate = [](const Pose&) { return QueryResult{}; };
  BodyState part;
  part.pose = start.pose;
  const LoopReport r = run_haptic_loop(device, none, config, simulated_loop_clock(), part);
  double deepest = 0, late_speed = 0;  // the peg's end below the floor (exact: both are flat)
  for (const FrameRecord& f : r.log) {
    deepest = std::max(deepest, fit.translation.z() - f.part.translation.z());
    if (f.time_s > 1.5) late_speed = std::max(late_speed, (f.part.translation - r.log.back().part.translation).norm());
  }
  const double floor_k = M_PI * 25 * p.scene.haptics.contact_stiffness_n_per_mm3;  // N / mm over the peg's end
  const double pull = 800 * 3e-3;                                                   // N, the coupling at 3 mm
  MESSAGE("deepest " << deepest << " mm, final z " << r.final_part.pose.translation.z() - fit.translation.z()
                     << " mm, sent " << r.log.back().sent.force.transpose() << " N, largest drift over the last 0.5 s "
                     << late_speed << " mm");
  CHECK(deepest <= model->skin + 1.5 * pull / floor_k);
  CHECK(r.final_part.pose.translation.z() - fit.translation.z() >= -(model->skin + 1.5 * pull / floor_k));
  CHECK(late_speed < 1e-4);  // at rest: no oscillation survives
  CHECK(r.log.back().sent.force.z() == doctest::Approx(pull).epsilon(0.05));  // the hand feels the wall
  CHECK(r.part_resets == 0);
}

namespace {

// The default scene's loop as `snapfit run` configures it (seed 000's energy at m' 8192
// times its gain, the coupling, the rigid contact), for scripted hands.
struct DefaultLoop {
  AssemblyPair pair;
  std::unique_ptr<QueryEngine> engine;
  LoopConfig config;
};

DefaultLoop& default_loop() {
  static DefaultLoop d = [] {
    DefaultLoop l;
    const Scene scene = test::shipped_scene("default.json");
    test::ShippedEngine shipped = test::shipped_engine(scene);
    l.pair = std::move(shipped.pair);
    l.engine = std::move(shipped.engine);
    const TuningResult fixed = pick_modes({TimingPoint{8192, 0, 0, 0, 1}}, scene.frame_budget_ms, 0.25);
    double force_scale = 0;
    l.config = loop_config_for(scene, l.pair.part(2).mesh, l.pair.spectra.spacing, *l.engine, fixed, force_scale,
                               rigid_contact_for(scene, l.pair.part(1).mesh, l.pair.part(2).mesh,
                                                 l.pair.spectra.spacing));
    return l;
  }();
  return d;
}

// Runs the default loop for a hand moving through `keys` from part 2 at keys[0]; the
// deepest contact interpenetration on the way goes to `deepest`.
LoopReport run_hand(const std::vector<Keyframe>& keys, double& deepest) {
  DefaultLoop& l = default_loop();
  ScriptedDevice device(Trajectory{keys}, DeviceLimits{l.pair.scene.haptics.max_force_n, l.pair.scene.haptics.max_torque_nm});
  LoopConfig config = l.config;
  config.duration_s = keys.back().time_s;
  config.keep_log = true;
  BodyState part;
  part.pose = keys.front().pose;
  const LoopReport r = run_haptic_loop(device, wrench_evaluator(*l.engine), config, simulated_loop_clock(), part);
  deepest = 0;
  for (const FrameRecord& f : r.log) deepest = std::max(deepest, f.contact_depth);
  return r;
}

}  // namespace

// The hand can take the part back out: the fit's attraction (seed 000's energy times the
// loop's gain) stays weaker than the hand, the walls hold on the way. The peg's end is
// at the block's top face 20 mm above the fit.
TEST_CASE("rigid contact: a hand pulling the peg out of the fit gets it out") {
  const Pose fit = *default_loop().pair.scene.assembled_pose;
  const Pose out = moved(fit, Eigen::Vector3d(0, 0, 26), Eigen::Vector3d::Zero());
  double deepest = 0;
  const LoopReport r = run_hand({{0.0, fit}, {0.3, fit}, {1.3, out}, {1.8, out}}, deepest);
  const Eigen::Vector3d lag = r.final_part.pose.translation - out.translation;
  MESSAGE("part ends " << lag.transpose() << " mm from the hand, deepest contact " << deepest << " mm, largest force "
                       << r.log.back().sent.force.norm() << " N at the end");
  CHECK(r.final_part.pose.translation.z() - fit.translation.z() >= 20 + 5);  // clear of the block
  CHECK(lag.norm() <= 0.5);  // the coupling alone holds it, the fit no longer pulls
  CHECK(deepest <= 0.3);
  CHECK(r.part_resets == 0);
}

// From a shallow engagement (the peg 2 mm into the hole), a hand moving 10 mm sideways
// and 4 mm up: the wall stops the sideways motion until the peg has lifted out (it may
// tilt), then the part follows the hand.
TEST_CASE("rigid contact: a hand pulling sideways out of a shallow engagement gets the peg out") {
  const Pose fit = *default_loop().pair.scene.assembled_pose;
  const Pose shallow = moved(fit, Eigen::Vector3d(0, 0, 18), Eigen::Vector3d::Zero());
  const Pose away = moved(fit, Eigen::Vector3d(10, 0, 22), Eigen::Vector3d::Zero());
  double deepest = 0;
  const LoopReport r = run_hand({{0.0, shallow}, {0.3, shallow}, {1.3, away}, {2.0, away}}, deepest);
  const Eigen::Vector3d lag = r.final_part.pose.translation - away.translation;
  MESSAGE("part ends " << lag.transpose() << " mm from the hand, deepest contact " << deepest << " mm");
  CHECK(r.final_part.pose.translation.x() - fit.translation.x() >= 9);  // beside the hole, out of it
  CHECK(lag.norm() <= 0.5);
  CHECK(deepest <= 0.3);
  CHECK(r.part_resets == 0);
}

// A part that is not watertight has no defined inside: the contact is off, and says
// which part and why, instead of pushing by a meaningless sign.
TEST_CASE("rigid contact: an open part turns the contact off with a reason") {
  const ShippedPair& p = default_pair();
  Mesh open = p.pair.part(2).mesh;
  open.triangles.pop_back();
  std::string why;
  CHECK(rigid_contact_for(p.scene, p.pair.part(1).mesh, open, p.pair.grids.spacing, &why) == nullptr);
  MESSAGE(why);
  CHECK(why.find("part 2 is not watertight") != std::string::npos);
  CHECK(why.find("haptics.contact") != std::string::npos);
  std::string none = "stale";
  Scene off = p.scene;
  off.haptics.contact = false;
  CHECK(rigid_contact_for(off, p.pair.part(1).mesh, open, p.pair.grids.spacing, &none) == nullptr);
  CHECK(none.empty());  // turned off by the scene: nothing to explain
}
