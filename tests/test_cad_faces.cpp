// Analytic faces from STEP files (io/occt_shapes.h analytic_faces_of, carried by
// io/cad_load.h to the scene's parts): the shipped scenes/parts/peg.step and
// hole_block.step against the dimensions of scenes/default.json's procedural parts they
// were written from (radii, axes, axial ranges, the floor and the top with its hole, peg
// or hole from the face orientation), a chamfered peg's cone, a placed solid's faces, and
// the hybrid on the STEP scene: concentric while the peg goes down its hole, then the
// floor's planar constraint; a part from a mesh file runs as plain VPS, said so.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/cad_load.h"
#include "io/face_codec.h"
#include "io/mesh_export.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/vps/vps_hybrid.h"
#include "snapfit/error.h"
#include "tests/cad_fixtures.h"
#include "tests/test_support.h"

namespace snapfit {
namespace {

const std::string kSource = SNAPFIT_SOURCE_DIR;

// The procedural part of scenes/default.json (1: the hole block, 2: the peg), which
// tests/tools/make_cad_parts wrote scenes/parts/*.step from.
double number(int part, const char* name) {
  const Scene scene = load_scene(kSource + "/scenes/default.json");
  return (part == 1 ? scene.part1 : scene.part2).procedural->numbers.at(name);
}

using test::with_deflection;

std::vector<const AnalyticFace*> of_kind(const std::vector<AnalyticFace>& faces, FaceKind kind) {
  std::vector<const AnalyticFace*> out;
  for (const AnalyticFace& f : faces)
    if (f.kind == kind) out.push_back(&f);
  return out;
}

// The plane with outward normal `n` through the point (0, 0, z) (or (x, 0, 0) for a side).
const AnalyticFace* plane_with(const std::vector<AnalyticFace>& faces, const Eigen::Vector3d& n,
                               const Eigen::Vector3d& through) {
  for (const AnalyticFace* f : of_kind(faces, FaceKind::plane))
    if (f->axis.isApprox(n, 1e-9) && std::abs((through - f->origin).dot(n)) < 1e-9) return f;
  return nullptr;
}

// The axial range of a revolution face along +z, whichever sense its axis has.
std::pair<double, double> z_range(const AnalyticFace& f) {
  const double z0 = f.origin.z() + f.a0 * f.axis.z(), z1 = f.origin.z() + f.a1 * f.axis.z();
  return {std::min(z0, z1), std::max(z0, z1)};
}

}  // namespace

TEST_CASE("cad faces: the shipped STEP peg's cylinder and end discs match scenes/default.json's peg") {
  const double r = number(2, "radius"), length = number(2, "length");
  const CadMesh peg = load_cad_mesh(kSource + "/scenes/parts/peg.step", with_deflection(0.06));  // an INCH file
  CHECK(peg.facts.planes == 2);
  CHECK(peg.facts.cylinders == 1);
  CHECK(peg.facts.cones == 0);
  CHECK(peg.facts.other_faces == 0);
  REQUIRE(peg.faces.size() == 3);
  const auto cylinders = of_kind(peg.faces, FaceKind::cylinder);
  REQUIRE(cylinders.size() == 1);
  const AnalyticFace& side = *cylinders[0];
  CHECK(side.radius() == doctest::Approx(r).epsilon(1e-9));
  CHECK(side.r0 == doctest::Approx(side.r1).epsilon(1e-12));
  CHECK(std::abs(side.axis.z()) == doctest::Approx(1).epsilon(1e-12));
  CHECK(side.origin.head<2>().norm() == doctest::Approx(0).epsilon(1e-9));
  CHECK(z_range(side).first == doctest::Approx(0).epsilon(1e-9));
  CHECK(z_range(side).second == doctest::Approx(length).epsilon(1e-9));
  CHECK(side.material_inside);  // a peg
  // The end discs: outward normals -z at the bottom, +z at the top, radius r about the axis.
  const AnalyticFace* bottom = plane_with(peg.faces, -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  const AnalyticFace* top = plane_with(peg.faces, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, 0, length));
  REQUIRE(bottom);
  REQUIRE(top);
  for (const AnalyticFace* disc : {bottom, top}) {
    CHECK(disc->r_out == doctest::Approx(r).epsilon(1e-9));
    CHECK(disc->origin.head<2>().norm() == doctest::Approx(0).epsilon(1e-9));
    CHECK(disc->holes.empty());
  }
  // Every vertex of the tessellation lies on one of the faces (within the deflection).
  for (const Eigen::Vector3d& v : peg.mesh.vertices) {
    double best = 1e9;
    for (const AnalyticFace& f : peg.faces) best = std::min(best, face_distance(f, v));
    CHECK(best <= 0.06 + 1e-9);
  }
}

TEST_CASE(
    "cad faces: the shipped STEP hole block's wall, countersink, floor and top match scenes/default.json's block") {
  const double r = number(1, "peg_radius") + number(1, "clearance"), depth = number(1, "hole_depth");
  const double chamfer = number(1, "chamfer"), half = 0.5 * number(1, "width"), height = number(1, "height");
  const CadMesh block = load_cad_mesh(kSource + "/scenes/parts/hole_block.step", with_deflection(0.06));
  CHECK(block.facts.planes == 7);  // top, 4 sides, bottom, floor
  CHECK(block.facts.cylinders == 1);
  CHECK(block.facts.cones == 1);
  const auto cylinders = of_kind(block.faces, FaceKind::cylinder), cones = of_kind(block.faces, FaceKind::cone);
  REQUIRE(cylinders.size() == 1);
  REQUIRE(cones.size() == 1);
  const AnalyticFace& wall = *cylinders[0];
  CHECK(wall.radius() == doctest::Approx(r).epsilon(1e-9));
  CHECK(std::abs(wall.axis.z()) == doctest::Approx(1).epsilon(1e-12));
  CHECK(wall.origin.head<2>().norm() == doctest::Approx(0).epsilon(1e-9));
  CHECK(z_range(wall).first == doctest::Approx(-depth).epsilon(1e-9));
  CHECK(z_range(wall).second == doctest::Approx(-chamfer).epsilon(1e-9));
  CHECK_FALSE(wall.material_inside);  // a hole
  // The 45-degree countersink: radius r at z = -chamfer, r + chamfer at the top.
  const AnalyticFace& sink = *cones[0];
  CHECK_FALSE(sink.material_inside);
  const auto [lo, hi] = z_range(sink);
  CHECK(lo == doctest::Approx(-chamfer).epsilon(1e-9));
  CHECK(hi == doctest::Approx(0).epsilon(1e-9));
  const double r_at_lo = sink.a0 * sink.axis.z() < sink.a1 * sink.axis.z() ? sink.r0 : sink.r1;
  const double r_at_hi = sink.a0 * sink.axis.z() < sink.a1 * sink.axis.z() ? sink.r1 : sink.r0;
  CHECK(r_at_lo == doctest::Approx(r).epsilon(1e-9));
  CHECK(r_at_hi == doctest::Approx(r + chamfer).epsilon(1e-9));
  // The floor: normal up (out of the material, into the hole), a disc of the hole's radius.
  const AnalyticFace* floor = plane_with(block.faces, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, 0, -depth));
  REQUIRE(floor);
  CHECK(floor->r_out == doctest::Approx(r).epsilon(1e-9));
  CHECK(floor->origin.head<2>().norm() == doctest::Approx(0).epsilon(1e-9));
  // The top: the square with the countersink's entry cut out.
  const AnalyticFace* top = plane_with(block.faces, Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  REQUIRE(top);
  REQUIRE(top->holes.size() == 1);
  CHECK(top->holes[0].radius == doctest::Approx(r + chamfer).epsilon(1e-9));
  CHECK(top->holes[0].centre.norm() == doctest::Approx(0).epsilon(1e-9));
  CHECK(top->lo.head<2>().isApprox(Eigen::Vector2d(-half, -half), 1e-9));
  CHECK(top->hi.head<2>().isApprox(Eigen::Vector2d(half, half), 1e-9));
  CHECK(face_distance(*top, Eigen::Vector3d(0, 0, 0)) == doctest::Approx(r + chamfer).epsilon(1e-9));  // over the hole
  CHECK(face_distance(*top, Eigen::Vector3d(10, 0, 0.2)) == doctest::Approx(0.2).epsilon(1e-9));
  // The box's sides and bottom, normals outward.
  for (const Eigen::Vector3d& n :
       {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(0, 1, 0), Eigen::Vector3d(0, -1, 0)})
    CHECK(plane_with(block.faces, n, half * n));
  CHECK(plane_with(block.faces, -Eigen::Vector3d::UnitZ(), Eigen::Vector3d(0, 0, -height)));

  // Through the import child's reply and back, unchanged.
  std::size_t used = 0;
  const std::string bytes = encode_faces(block.faces);
  const std::vector<AnalyticFace> back = decode_faces("x", bytes + "tail", used);
  CHECK(used == bytes.size());
  REQUIRE(back.size() == block.faces.size());
  for (std::size_t i = 0; i < back.size(); ++i) {
    CHECK(back[i].kind == block.faces[i].kind);
    CHECK(back[i].origin == block.faces[i].origin);
    CHECK(back[i].holes.size() == block.faces[i].holes.size());
    CHECK(back[i].material_inside == block.faces[i].material_inside);
  }
  CHECK_THROWS_WITH(decode_faces("x.step", bytes.substr(0, bytes.size() / 2), used),
                    doctest::Contains("x.step: cannot read CAD file: malformed analytic faces"));
}

TEST_CASE("cad faces: a chamfered peg's cone, a scale, and a placed solid's faces") {
  const test::TempDir dir;
  const std::string file = dir.file("peg.step");
  test::write_cad_part(file, {"peg", {{"radius", 4}, {"length", 12}, {"chamfer", 1}}, {}});
  CadImportOptions o = with_deflection(0.05);
  o.scale = 2;
  const CadMesh peg = load_cad_mesh(file, o);
  const auto cones = of_kind(peg.faces, FaceKind::cone);
  REQUIRE(cones.size() == 1);
  CHECK(cones[0]->material_inside);  // a peg's tip
  const auto [lo, hi] = z_range(*cones[0]);
  CHECK(lo == doctest::Approx(0).epsilon(1e-9));
  CHECK(hi == doctest::Approx(2 * 1).epsilon(1e-9));
  CHECK(std::min(cones[0]->r0, cones[0]->r1) == doctest::Approx(2 * 3).epsilon(1e-9));
  CHECK(std::max(cones[0]->r0, cones[0]->r1) == doctest::Approx(2 * 4).epsilon(1e-9));
  const auto cylinders = of_kind(peg.faces, FaceKind::cylinder);
  REQUIRE(cylinders.size() == 1);
  CHECK(cylinders[0]->radius() == doctest::Approx(8).epsilon(1e-9));
  CHECK(z_range(*cylinders[0]).second == doctest::Approx(24).epsilon(1e-9));

  // The second instance of a box is placed 10 mm along +x: its faces move with it.
  const std::string boxes = dir.file("boxes.step");
  test::write_cad_instances(boxes, {"box", {0, 0, 0}, {1, 2, 3}}, 10);
  CadImportOptions second = with_deflection(0.05);
  second.solid = "box [2]";
  const CadMesh placed = load_cad_mesh(boxes, second);
  REQUIRE(placed.faces.size() == 6);
  CHECK(placed.facts.other_faces == 0);
  CHECK(plane_with(placed.faces, -Eigen::Vector3d::UnitX(), Eigen::Vector3d(10, 0, 0)));
  CHECK(plane_with(placed.faces, Eigen::Vector3d::UnitX(), Eigen::Vector3d(11, 0, 0)));
  CHECK(plane_with(placed.faces, Eigen::Vector3d::UnitZ(), Eigen::Vector3d(10.5, 1, 3)));
}

TEST_CASE("cad faces: the STEP peg and hole as vps_hybrid engage concentric down the hole, then the floor's planar") {
  Scene scene = load_scene(kSource + "/scenes/peg_hole_step.json");
  scene.method = Method::vps_hybrid;
  scene.vps.voxel_size = 0.5;
  const AssemblyPair pair = prepare_assembly_pair(scene);
  REQUIRE(pair.part(1).faces.size() == 9);
  REQUIRE(pair.part(2).faces.size() == 3);
  const CouplingParams coupling = coupling_for(scene, pair.part(2).mesh);
  const HybridModel model =
      hybrid_model(vps_model_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing, coupling),
                   pair.part(1).faces, pair.part(2).faces, coupling);
  CHECK(std::count_if(model.voxel_face.begin(), model.voxel_face.end(), [](std::int16_t f) { return f >= 0; }) > 0);
  CHECK(std::count_if(model.point_face.begin(), model.point_face.end(), [](std::int16_t f) { return f >= 0; }) > 0);

  // Straight down the axis at zero clearance to 0.1 below the floor (the assembled pose
  // puts the peg's bottom on it), 0.02 a frame, then held there.
  const double floor = scene.assembled_pose->translation.z();
  HybridState state = hybrid_state_for(model);
  const auto on_floor = [&](const ActiveConstraint& a) {
    const AnalyticFace& f = model.faces1[a.face1];
    return a.kind == ConstraintKind::planar && f.axis.isApprox(Eigen::Vector3d::UnitZ(), 1e-9) &&
           std::abs(f.origin.z() - floor) < 1e-9;
  };
  bool concentric_inside = false, floor_engaged = false, floor_early = false;
  int first_concentric = 0, first_floor = 0, frame = 0;
  std::vector<double> path;
  for (double z = 2; z > floor - 0.1; z -= 0.02) path.push_back(z);
  path.insert(path.end(), 100, floor - 0.1);  // held: the ramp takes 50 frames
  for (const double z : path) {
    ++frame;
    BodyState b;
    b.pose.translation = Eigen::Vector3d(0, 0, z);
    hybrid_wrench(model, state, b);
    for (const ActiveConstraint& a : state.active) {
      if (a.kind == ConstraintKind::concentric && a.phase > 0.99 && z < -2 && z > floor + 2) concentric_inside = true;
      if (a.kind == ConstraintKind::concentric && !first_concentric) first_concentric = frame;
      if (on_floor(a) && !first_floor) first_floor = frame;
      if (on_floor(a) && a.phase > 0.99) floor_engaged = true;
      if (on_floor(a) && z > floor + 2 * scene.vps.voxel_size.value()) floor_early = true;
    }
  }
  MESSAGE("STEP hybrid: concentric from frame " << first_concentric << ", the floor's planar from frame "
                                                << first_floor);
  CHECK(concentric_inside);
  CHECK(floor_engaged);
  CHECK_FALSE(floor_early);  // recognised only when the faces are within the tolerance (2 voxels)
  CHECK(first_concentric > 0);
  CHECK(first_floor > first_concentric);
}

TEST_CASE("cad faces: snapfit run plays the STEP scene as vps_hybrid with its faces, a mesh file part as plain VPS") {
  nlohmann::json scene;
  std::ifstream(kSource + "/scenes/peg_hole_step.json") >> scene;
  for (const char* part : {"part1", "part2"})
    scene[part]["mesh"] = kSource + "/scenes/" + scene[part]["mesh"].get<std::string>();
  scene["method"] = "vps_hybrid";
  scene["vps"] = {{"voxel_size", 1.0}};
  scene.erase("trajectory");
  const test::TempDir dir;
  test::write_text(dir.file("step.json"), scene.dump());
  const test::Command run = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("step.json") +
                                              " --simulated-time --out " + dir.file("out"));
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("vps_hybrid: 9 + 3 analytic faces") != std::string::npos);
  nlohmann::json summary;
  std::ifstream(dir.file("out/summary.json")) >> summary;
  CHECK(summary["vps"]["hybrid"]["engaged"] == true);

  // The peg as an OBJ file: no faces, plain VPS, and the console says which part and why.
  const CadMesh peg = load_cad_mesh(kSource + "/scenes/parts/peg.step", with_deflection(0.05));
  write_obj(peg.mesh, dir.file("peg.obj"));
  scene["part2"].erase("cad");
  scene["part2"]["mesh"] = dir.file("peg.obj");
  test::write_text(dir.file("obj.json"), scene.dump());
  const test::Command plain = test::run_command(std::string(SNAPFIT_CLI_PATH) + " run " + dir.file("obj.json") +
                                                " --simulated-time --out " + dir.file("obj"));
  INFO(plain.output);
  REQUIRE(plain.status == 0);
  CHECK(plain.output.find("part 'peg' (a mesh file) has no analytic faces: running as plain Voxmap PointShell") !=
        std::string::npos);
  nlohmann::json s2;
  std::ifstream(dir.file("obj/summary.json")) >> s2;
  CHECK(s2["vps"]["hybrid"]["engaged"] == false);
}

}  // namespace snapfit
