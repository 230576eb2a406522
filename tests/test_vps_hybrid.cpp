// The Voxmap PointShell - constraint hybrid (scheduler/vps/constraint_recognition.h,
// scheduler/vps/vps_hybrid.h): recognition between the procedural peg's and hole's faces
// (concentric, planar; none for a cylinder against a plane, cylinders of different radii,
// two pegs, tilted axes), engagement (eq. 15-17), and a scripted insertion down to the
// floor and back out: concentric while inserting, then planar at the floor, both
// released outside, with bounded steps of the blend weights between frames; the scene's
// vps.hybrid section, x_full and the face region; `snapfit run` with a vps_hybrid scene
// (constraint per frame in loop.csv and summary.json; with the paper's blend it assembles
// below the voxel size, the weight steps little and the force sent no more than 1.5x plain
// VPS's; with the default blend it assembles at zero clearance) and on the three-peg pair.
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <doctest/doctest.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mesh/procedural/procedural_parts.h"
#include "scheduler/vps/vps_hybrid.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

int face(const std::vector<AnalyticFace>& faces, const char* name) {
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (std::strcmp(faces[i].name, name) == 0) return static_cast<int>(i);
  FAIL("no face " << name);
  return -1;
}

constexpr double kVoxel = 0.5, kDepth = 10, kClearance = 0.2;

const ProceduralPartSpec kPeg{"peg", {{"radius", 5}, {"length", 20}, {"chamfer", 0.5}}, {}};
const ProceduralPartSpec kHole{"hole_block",
                               {{"peg_radius", 5},
                                {"clearance", kClearance},
                                {"hole_depth", kDepth},
                                {"width", 20},
                                {"height", 15},
                                {"chamfer", 0.5}},
                               {}};

HybridModel peg_in_hole_model(double ramp_s) {
  VpsModel vps;
  vps.voxmap = build_voxmap(make_procedural_part(kHole), kVoxel, 2);
  vps.shell = build_point_shell(make_procedural_part(kPeg), kVoxel);
  vps.stiffness = 800;
  vps.braking = 0;
  vps.metres_per_unit = 1e-3;
  vps.period_s = 1e-3;
  HybridParams params;
  params.ramp_s = ramp_s;
  return hybrid_model(std::move(vps), procedural_part_faces(kHole), procedural_part_faces(kPeg), CouplingParams{},
                      params);
}

// The columns of loop.csv the run test reads.
struct LoopColumns {
  std::vector<int> constraint;
  std::vector<double> weight;
  std::vector<Eigen::Vector3d> sent;
  std::size_t frames() const { return weight.size(); }
  double max_sent_step() const {
    double m = 0;
    for (std::size_t i = 1; i < sent.size(); ++i) m = std::max(m, (sent[i] - sent[i - 1]).norm());
    return m;
  }
};

LoopColumns read_loop(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  for (std::stringstream s(line); std::getline(s, line, ',');) names.push_back(line);
  const auto column = [&](const char* name) {
    const auto it = std::find(names.begin(), names.end(), name);
    REQUIRE(it != names.end());
    return static_cast<std::size_t>(it - names.begin());
  };
  const std::size_t c = column("constraint"), x = column("constraint_x"), fx = column("sent_fx");
  LoopColumns out;
  while (std::getline(in, line)) {
    std::vector<double> v;
    for (std::stringstream s(line); std::getline(s, line, ',');) v.push_back(std::stod(line));
    out.constraint.push_back(static_cast<int>(v.at(c)));
    out.weight.push_back(v.at(x));
    out.sent.emplace_back(v.at(fx), v.at(fx + 1), v.at(fx + 2));
  }
  return out;
}

Pose at(double x, double z) {
  Pose p;
  p.translation = Eigen::Vector3d(x, 0, z);
  return p;
}

}  // namespace

TEST_CASE("vps hybrid: recognition between the peg's and the hole's faces") {
  const auto hole = procedural_part_faces(kHole), peg = procedural_part_faces(kPeg);
  const auto thin = procedural_part_faces({"peg", {{"radius", 3}, {"length", 20}}, {}});
  RecognitionTolerance tol{2 * kVoxel, 2 * kVoxel, 0.2};
  const AnalyticFace &wall = hole[face(hole, "hole wall")], &floor = hole[face(hole, "hole floor")];
  const AnalyticFace &side = peg[face(peg, "peg side")], &bottom = peg[face(peg, "peg bottom")];
  CHECK(recognise(wall, side, at(0.1, -3), tol) == ConstraintKind::concentric);
  CHECK(recognise(wall, side, at(0, -3), tol) == ConstraintKind::concentric);
  CHECK(recognise(wall, bottom, at(0, -3), tol) == ConstraintKind::none);      // cylinder against plane
  CHECK(recognise(floor, side, at(0, -kDepth), tol) == ConstraintKind::none);  // plane against cylinder
  CHECK(recognise(wall, thin[face(thin, "peg side")], at(0, -3), tol) == ConstraintKind::none);  // radii differ
  CHECK(recognise(side, side, at(0, -3), tol) == ConstraintKind::none);                          // peg against peg
  Pose tilted = at(0, -3);
  tilted.rotation = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitX());
  CHECK(recognise(wall, side, tilted, tol) == ConstraintKind::none);
  CHECK(recognise(wall, side, at(3, -3), tol) == ConstraintKind::none);  // axes far apart
  CHECK(recognise(floor, bottom, at(0, -kDepth), tol) == ConstraintKind::planar);
  CHECK(recognise(floor, peg[face(peg, "peg top")], at(0, -kDepth - 20), tol) == ConstraintKind::none);  // not opposed
  CHECK(recognise(floor, bottom, at(0, -kDepth + 3), tol) == ConstraintKind::none);  // too far above

  // Engagement, eq. 15-17: 1 on the constraint, 0.5 + 0.5 exp(-d/s) for a pure offset d
  // beyond the play (the radii's difference, the clearance).
  const ConstraintOffset on = constraint_offset(ConstraintKind::concentric, wall, side, at(0, -5));
  CHECK(engagement(on, kVoxel) == doctest::Approx(1));
  CHECK(on.depth == doctest::Approx(5 - 0.5 - 0.5));  // overlap of wall [-10, -0.5] and side [-4.5, 15]
  const ConstraintOffset off = constraint_offset(ConstraintKind::concentric, wall, side, at(0.25, -5));
  CHECK(off.d.x() == doctest::Approx(-0.25));
  CHECK(off.play == doctest::Approx(kClearance).epsilon(1e-3));
  CHECK(engagement(off, kVoxel) == doctest::Approx(0.5 + 0.5 * std::exp(-(0.25 - off.play) / kVoxel)));
  const ConstraintOffset within = constraint_offset(ConstraintKind::concentric, wall, side, at(0.15, -5));
  CHECK(engagement(within, kVoxel) == doctest::Approx(1));  // inside the play
  const ConstraintOffset turned = constraint_offset(ConstraintKind::concentric, wall, side, tilted);
  CHECK(turned.theta == doctest::Approx(0.3));
  // theta_0 = s / l: the turn's term is exp(-theta l / s).
  CHECK(engagement(turned, kVoxel) ==
        doctest::Approx(0.5 * std::exp(-0.3 * turned.depth / kVoxel) +
                        0.5 * std::exp(-std::max(0.0, turned.d.norm() - turned.play) / kVoxel)));
}

TEST_CASE("vps hybrid: bad parameters are refused") {
  VpsModel vps;
  vps.voxmap = build_voxmap(make_procedural_part(kHole), 1.0, 1);
  vps.shell = build_point_shell(make_procedural_part(kPeg), 1.0);
  HybridParams p;
  p.alignment_fraction = 1.5;
  CHECK_THROWS_WITH(hybrid_model(vps, {}, {}, CouplingParams{}, p), doctest::Contains("alignment fraction"));
  p = HybridParams{};
  p.x_release = 0.9;
  CHECK_THROWS_WITH(hybrid_model(vps, {}, {}, CouplingParams{}, p), doctest::Contains("release < engage"));
}

TEST_CASE(
    "vps hybrid: the scene's vps.hybrid section sets the parameters, x_full saturates the weight, the face region") {
  nlohmann::json j;
  std::ifstream(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/peg_hole_clearance_0p5.json") >> j;
  j["method"] = "vps_hybrid";
  j["vps"]["hybrid"] = {{"rotation_fraction", 0.8}, {"x_full", 0.8}, {"angle_tolerance_deg", 5},
                        {"region", "face"},         {"ramp_s", 0},   {"offset_tolerance", 0.3}};
  const Scene scene = parse_scene(j.dump(), "hybrid.json");
  const HybridParams p = hybrid_params_for(scene);
  CHECK(p.rotation_fraction == 0.8);
  CHECK(p.alignment_fraction == 0.5);
  CHECK(p.x_full == 0.8);
  CHECK(p.region == HybridRegion::face);
  CHECK(p.tolerance.angle == doctest::Approx(5 * 3.14159265358979323846 / 180));
  CHECK(p.tolerance.offset == 0.3);
  CHECK(p.tolerance.radius == 0);  // left to the voxel size
  CouplingParams coupling;
  coupling.stiffness = 1000;
  coupling.rot_stiffness = 2;
  VpsModel vps;
  vps.voxmap = build_voxmap(make_procedural_part(kHole), kVoxel, 2);
  vps.shell = build_point_shell(make_procedural_part(kPeg), kVoxel);
  vps.stiffness = 800;
  vps.metres_per_unit = 1e-3;
  vps.period_s = 1e-3;
  const HybridModel m = hybrid_model(vps, procedural_part_faces(kHole), procedural_part_faces(kPeg), coupling, p);
  CHECK(m.k_a_n_per_m == 500);
  CHECK(m.k_r_nm_per_rad == doctest::Approx(1.6));
  CHECK(m.params.tolerance.radius == 2 * kVoxel);

  // A peg tilted in its hole so that x ~ 0.9 (the theta term of eq. 15 below 1): with the
  // paper's weight (x_full 1) the blend weight is x; with x_full 0.8 it is 1.
  const auto weight_at = [&](double x_full, HybridRegion region, QueryWrench* region_force) {
    HybridParams q;
    q.ramp_s = 0;
    q.x_full = x_full;
    q.region = region;
    const HybridModel model = hybrid_model(vps, procedural_part_faces(kHole), procedural_part_faces(kPeg), coupling, q);
    HybridState state = hybrid_state_for(model);
    BodyState b;
    b.pose = at(0.35, -6);  // beyond the 0.2 play: in contact with the wall
    b.pose.rotation = Eigen::AngleAxisd(0.004, Eigen::Vector3d::UnitY());
    HybridResult r;
    for (int i = 0; i < 3; ++i) r = hybrid_wrench(model, state, b);  // recognise, then engage
    if (region_force) *region_force = state.region[0];
    return std::pair<double, double>(r.x, state.active[0].x);
  };
  QueryWrench pair_region, face_region;
  const auto [w_paper, x] = weight_at(1.0, HybridRegion::pair, &pair_region);
  MESSAGE("tilted peg: x " << x);
  REQUIRE(x > 0.75);
  REQUIRE(x < 0.999);
  CHECK(w_paper == doctest::Approx(x));
  CHECK(weight_at(0.8, HybridRegion::pair, nullptr).first == doctest::Approx(std::min(1.0, x / 0.8)));
  CHECK(weight_at(x, HybridRegion::pair, nullptr).first == doctest::Approx(1.0));
  // The face region holds at least the pair region's contacts: every contact on the wall.
  weight_at(1.0, HybridRegion::face, &face_region);
  CHECK(face_region.force.norm() >= pair_region.force.norm() - 1e-12);
}

TEST_CASE("vps hybrid: a scripted insertion engages concentric, then planar at the floor, and releases both") {
  // Part 2 goes down the hole 0.3 off its axis (beyond the clearance: it touches the wall),
  // is pressed 0.1 into the floor, pulled onto the axis, held, then pulled out and away.
  const double floor = -kDepth - 0.1;
  std::vector<Pose> path;
  for (double z = 2; z > floor; z -= 0.02) path.push_back(at(0.3, z));
  for (double x = 0.3; x > 0; x -= 0.005) path.push_back(at(x, floor));
  for (int i = 0; i < 200; ++i) path.push_back(at(0, floor));
  for (double z = floor; z < 4; z += 0.02) path.push_back(at(0, z));
  for (int i = 0; i < 200; ++i) path.push_back(at(0, 4));

  // The largest change of a constraint's blend weight phase * x between frames, and
  // whether concentric was fully engaged inside the hole and both at the floor.
  auto run = [&](double ramp_s, double& max_step, bool& concentric, bool& both, int& engaged_at_end) {
    const HybridModel model = peg_in_hole_model(ramp_s);
    HybridState state = hybrid_state_for(model);
    max_step = 0;
    concentric = both = false;
    std::array<double, kMaxConstraints> last{};
    for (std::size_t i = 0; i < path.size(); ++i) {
      BodyState b;
      b.pose = path[i];
      const HybridResult r = hybrid_wrench(model, state, b);
      bool has_c = false, has_p = false;
      for (int k = 0; k < kMaxConstraints; ++k) {
        const ActiveConstraint& a = state.active[k];
        const double w = a.kind == ConstraintKind::none ? 0.0 : a.phase * a.x;
        max_step = std::max(max_step, std::abs(w - last[k]));
        last[k] = w;
        has_c |= a.kind == ConstraintKind::concentric && a.phase > 0.99;
        has_p |= a.kind == ConstraintKind::planar && a.phase > 0.99;
      }
      if (path[i].translation.z() > -kDepth + 2 && path[i].translation.z() < -2) concentric |= has_c;
      both |= has_c && has_p;
      engaged_at_end = r.engaged;
    }
  };
  double ramped_step = 0, instant_step = 0;
  bool concentric = false, both = false;
  int end = -1;
  run(0.05, ramped_step, concentric, both, end);
  CHECK(concentric);
  CHECK(both);
  CHECK(end == 0);
  bool c2 = false, b2 = false;
  int e2 = -1;
  run(0.0, instant_step, c2, b2, e2);
  MESSAGE("largest step of a blend weight between frames: ramped " << ramped_step << ", instant " << instant_step);
  // Phased in and out over 50 frames: 1/50 per frame, plus what x itself changes along
  // this path (|d| moves by at most 0.02 per frame: 0.5 * 0.02 / s = 0.02); switched at
  // once, the weight jumps by x >= x_engage.
  CHECK(ramped_step <= 0.02 + 0.02 + 1e-9);
  CHECK(instant_step >= 0.75);
}

TEST_CASE(
    "vps hybrid: snapfit run plays a vps_hybrid scene with the constraint per frame, and the three-peg pair with its "
    "faces") {
  // The shipped peg scene at 0.1 mm clearance (below the voxel: the peg touches the wall)
  // as "method": "vps_hybrid" at a quarter-millimetre voxel, with the paper's blend (eq.
  // 13's x, the pair region, k_R half the coupling's).
  nlohmann::json scene;
  std::ifstream(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/peg_hole_clearance_0p5.json") >> scene;
  scene["part1"]["procedural"]["clearance"] = 0.1;
  scene["method"] = "vps_hybrid";
  scene["vps"] = {{"voxel_size", 0.25}, {"hybrid", {{"x_full", 1}, {"region", "pair"}, {"rotation_fraction", 0.5}}}};
  const test::TempDir dir;
  test::write_text(dir.file("hybrid.json"), scene.dump());
  const test::Command run = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("hybrid.json") +
                                              " --simulated-time --out " + dir.file("out"));
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("analytic faces") != std::string::npos);
  nlohmann::json summary;
  std::ifstream(dir.file("out/summary.json")) >> summary;
  CHECK(summary["method"] == "vps_hybrid");
  const nlohmann::json& h = summary["vps"]["hybrid"];
  CHECK(h["engaged"] == true);
  CHECK(h["faces1"] == 8);  // top, 4 sides, bottom, wall, floor (no chamfer)
  CHECK(h["faces2"] == 3);  // bottom, side, top
  CHECK(h["frames_concentric"].get<int>() > 0);
  CHECK(h["max_constraint_x"].get<double>() > 0.5);
  CHECK(h["max_constraint_x"].get<double>() <= 1.0);
  // Plain VPS stops about 3.9 mm short here: the voxel is larger than the clearance.
  CHECK(summary["haptic_loop"]["assembled"] == true);
  // loop.csv carries the constraint (1 concentric) and its weight per frame.
  const LoopColumns hybrid_loop = read_loop(dir.file("out/loop.csv"));
  REQUIRE(hybrid_loop.frames() > 5000);
  CHECK(std::count(hybrid_loop.constraint.begin(), hybrid_loop.constraint.end(), 1) ==
        h["frames_concentric"].get<int>());
  // Through engagement and release in the loop: the weight moves by at most the ramp's
  // 1/50 plus what x itself changes in a frame (the speed limit keeps that small), and
  // the force sent steps no more than plain VPS's on the same scene.
  double max_dx = 0;
  for (std::size_t i = 1; i < hybrid_loop.frames(); ++i)
    max_dx = std::max(max_dx, std::abs(hybrid_loop.weight[i] - hybrid_loop.weight[i - 1]));
  CHECK(max_dx <= 0.05);
  scene["method"] = "vps";
  test::write_text(dir.file("vps.json"), scene.dump());
  const test::Command vps_run = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("vps.json") +
                                                  " --simulated-time --out " + dir.file("vps_out"));
  REQUIRE(vps_run.status == 0);
  const double hybrid_step = hybrid_loop.max_sent_step(),
               vps_step = read_loop(dir.file("vps_out/loop.csv")).max_sent_step();
  MESSAGE("largest sent force step: hybrid " << hybrid_step << " N, plain VPS " << vps_step << " N; weight step "
                                             << max_dx);
  CHECK(hybrid_step <= 1.5 * vps_step);

  // At zero clearance with the default blend (x_full 0.8, the face region, k_R 0.9 of the
  // coupling's): it assembles where plain VPS stops short, the weight still steps by at
  // most the ramp's 1/50 plus what x / x_full changes in a frame, and the force sent
  // steps less than plain VPS's.
  scene["part1"]["procedural"]["clearance"] = 0;
  scene["method"] = "vps_hybrid";
  scene["vps"] = {{"voxel_size", 0.25}};
  test::write_text(dir.file("zero.json"), scene.dump());
  const test::Command zero = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("zero.json") +
                                               " --simulated-time --out " + dir.file("zero"));
  INFO(zero.output);
  REQUIRE(zero.status == 0);
  nlohmann::json zs;
  std::ifstream(dir.file("zero/summary.json")) >> zs;
  CHECK(zs["haptic_loop"]["assembled"] == true);
  const LoopColumns zero_loop = read_loop(dir.file("zero/loop.csv"));
  double zero_dx = 0;
  for (std::size_t i = 1; i < zero_loop.frames(); ++i)
    zero_dx = std::max(zero_dx, std::abs(zero_loop.weight[i] - zero_loop.weight[i - 1]));
  CHECK(zero_dx <= 0.05);
  scene["method"] = "vps";
  test::write_text(dir.file("zero_vps.json"), scene.dump());
  const test::Command zero_vps = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("zero_vps.json") +
                                                   " --simulated-time --out " + dir.file("zero_vps"));
  REQUIRE(zero_vps.status == 0);
  nlohmann::json zv;
  std::ifstream(dir.file("zero_vps/summary.json")) >> zv;
  CHECK(zv["haptic_loop"]["assembled"] == false);
  const double zero_step = zero_loop.max_sent_step(),
               zero_vps_step = read_loop(dir.file("zero_vps/loop.csv")).max_sent_step();
  MESSAGE("zero clearance: largest sent force step hybrid " << zero_step << " N, plain VPS " << zero_vps_step
                                                            << " N; weight step " << zero_dx);
  CHECK(zero_step <= zero_vps_step);

  // The three-peg pair has faces now (planes and cylinders; its fillets unlabelled): the
  // hybrid runs on it. A part without faces (a mesh file): tests/test_cad_faces.cpp.
  nlohmann::json three;
  std::ifstream(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/three_pegs.json") >> three;
  three["method"] = "vps_hybrid";
  three["vps"] = {{"voxel_size", 1.0}};
  three.erase("trajectory");
  test::write_text(dir.file("three.json"), three.dump());
  const test::Command pegs = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("three.json") +
                                               " --simulated-time --out " + dir.file("three"));
  INFO(pegs.output);
  REQUIRE(pegs.status == 0);
  CHECK(pegs.output.find("vps_hybrid: 15 + 15 analytic faces") != std::string::npos);
  nlohmann::json s3;
  std::ifstream(dir.file("three/summary.json")) >> s3;
  CHECK(s3["vps"]["hybrid"]["engaged"] == true);
}
