// The real-CAD pairs as shipped (scenes/cad/, scenes/parts/cad/; tests/cad_pairs.h): each
// STEP file reads back (io/cad_load.h) into a closed mesh of the volume its dimensions
// give in closed form, and at each scene's assembled pose the parts do not interpenetrate
// while part 2's seat touches part 1 (and 0.2 mm further along the insertion they would);
// and the shipped files are what tests/tools/make_cad_pairs writes.
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/cad_load.h"
#include "mesh/interpenetration.h"
#include "mesh/mesh_distance.h"
#include "mesh/mesh_report.h"
#include "snapfit/scene.h"
#include "tests/cad_pairs.h"
#include "tests/test_support.h"

namespace snapfit {
namespace {

using test::kPi;
// Fine tessellation, so that the mesh's volume is within deflection x area of the B-rep's.
constexpr double kDeflection = 0.002;
// Interpenetration and seat distance allowed at the assembled pose: the meshes of the
// scene's own tessellation (spacing / 40 = 0.015 mm) would be off by that much; these are finer.
constexpr double kTouch = 0.01;

// Volume a convex fillet of radius a removes from the circular edge of radius R between
// a cylinder's side and its end face (Pappus: the corner square less the quarter disc).
double fillet_cut(double R, double a) { return 2 * kPi * a * a * ((R - a) * (1 - kPi / 4) + a / 6); }
// Volume a 45-degree chamfer of leg c removes from an outer (convex) circular edge of
// radius R, and from an inner one (a bore's edge).
double chamfer_cut(double R, double c) { return kPi * c * c * (R - c / 3); }
double bore_chamfer_cut(double R, double c) { return kPi * c * c * (R + c / 3); }
// A square frustum of height h between sides s0 and s1.
double frustum(double s0, double s1, double h) { return h / 3 * (s0 * s0 + s1 * s1 + s0 * s1); }
// The area of a disc of radius R less the segment beyond the chord at distance a.
double d_area(double R, double a) {
  return kPi * R * R - (R * R * std::acos(a / R) - a * std::sqrt(R * R - a * a));
}
double disc(double r) { return kPi * r * r; }

// The closed-form volumes of each pair's parts (mm^3), in cad_pairs() order.
std::vector<std::pair<double, double>> expected_volumes() {
  const test::ScrewRodDims s;
  const test::RingShaftDims r;
  const test::SquarePegDims q;
  const test::DShaftDims d;
  const test::TwoPinDims p;
  const test::GroovedShaftDims g;
  const double hole_side = q.peg_side + 2 * q.clearance;
  const double groove_ring = disc(g.shaft_radius) - disc(g.shaft_radius - g.groove_depth);
  return {
      {2 * s.rod_half_length * s.rod_width * s.rod_thickness + disc(s.rod_width / 2) * s.rod_thickness -
           2 * disc(s.hole_radius) * s.rod_thickness,
       disc(s.head_radius) * s.head_height - fillet_cut(s.head_radius, s.head_fillet) +
           disc(s.shank_radius) * s.shank_length - chamfer_cut(s.shank_radius, s.tip_chamfer)},
      {disc(r.shoulder_radius) * r.shoulder_height + disc(r.shaft_radius) * r.shaft_length -
           chamfer_cut(r.shaft_radius, r.shaft_chamfer),
       (disc(r.ring_outer) - disc(r.ring_inner)) * r.ring_height - 2 * bore_chamfer_cut(r.ring_inner, r.bore_chamfer)},
      {q.block_side * q.block_side * q.block_height - hole_side * hole_side * q.hole_depth -
           (frustum(hole_side, hole_side + 2 * q.entry_chamfer, q.entry_chamfer) - hole_side * hole_side * q.entry_chamfer),
       q.peg_side * q.peg_side * (q.peg_length - q.peg_chamfer) +
           frustum(q.peg_side - 2 * q.peg_chamfer, q.peg_side, q.peg_chamfer)},
      {d.block_side * d.block_side * d.block_height - d_area(d.radius + d.clearance, d.flat + d.clearance) * d.hole_depth,
       d_area(d.radius, d.flat) * d.length},
      {p.plate_length * p.plate_width * p.block_height - 2 * disc(p.pin_radius + p.clearance) * p.hole_depth,
       p.plate_length * p.plate_width * p.plate_thickness +
           2 * (disc(p.pin_radius) * p.pin_length - chamfer_cut(p.pin_radius, p.pin_chamfer))},
      {(disc(g.collar_outer) - disc(g.shaft_radius + g.clearance)) * g.collar_height -
           bore_chamfer_cut(g.shaft_radius + g.clearance, g.entry_chamfer),
       disc(g.shaft_radius) * g.shaft_length - fillet_cut(g.shaft_radius, g.tip_fillet) -
           groove_ring * g.groove_width + disc(g.head_radius) * g.head_height -
           fillet_cut(g.head_radius, g.head_fillet)},
  };
}

std::vector<Eigen::Vector3d> ring_of(double radius, double z, int n = 8) {
  std::vector<Eigen::Vector3d> out;
  for (int k = 0; k < n; ++k) out.emplace_back(radius * std::cos(2 * kPi * k / n), radius * std::sin(2 * kPi * k / n), z);
  return out;
}

// Points of part 2's seat (its own frame) that touch part 1 when assembled, in
// cad_pairs() order: the screw's bearing face on the rod, the ring's face on the shoulder
// and its bore on the shaft (zero clearance), the square peg's and the D-shaft's ends on
// their holes' bottoms, the plate's underside on the block, the head's underside on the collar.
std::vector<std::vector<Eigen::Vector3d>> seats() {
  const test::ScrewRodDims s;
  const test::RingShaftDims r;
  const test::GroovedShaftDims g;
  std::vector<Eigen::Vector3d> ring = ring_of(0.5 * (r.ring_inner + r.ring_outer), 0);
  for (const Eigen::Vector3d& v : ring_of(r.ring_inner, r.ring_height / 2)) ring.push_back(v);
  return {ring_of(0.5 * (s.hole_radius + s.head_radius), 0),
          ring,
          {{2, 2, 0}, {-2, 2, 0}, {2, -2, 0}, {-2, -2, 0}},
          {{0, 2, 0}, {0, -2, 0}, {-3, 0, 0}, {2, 0, 0}},
          {{0, 5, 0}, {0, -5, 0}, {18, 5, 0}, {-18, -5, 0}},
          ring_of(g.collar_outer - 1, 0)};
}

Mesh load_part(const std::string& file) {
  CadImportOptions options;
  options.linear_deflection = kDeflection;
  options.angular_deflection_deg = 5;
  return load_cad_mesh(file, options).mesh;
}

TEST_CASE("real-CAD pairs: closed meshes of the closed-form volume, seated without interpenetration") {
  const auto volumes = expected_volumes();
  const auto seat_points = seats();
  const auto& pairs = test::cad_pairs();
  REQUIRE(pairs.size() == 6);
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const test::CadPairInfo& pair = pairs[k];
    CAPTURE(pair.name);
    const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/cad/" + pair.name + ".json");
    REQUIRE(scene.assembled_pose);
    const Pose assembled = *scene.assembled_pose;
    CHECK((assembled.translation - pair.assembled).norm() < 1e-9);
    CHECK(assembled.rotation.angularDistance(Eigen::Quaterniond::Identity()) < 1e-12);

    Mesh mesh[2];
    for (int part = 0; part < 2; ++part) {
      const PartSpec& spec = part == 0 ? scene.part1 : scene.part2;
      REQUIRE(spec.mesh_path);
      mesh[part] = load_part(*spec.mesh_path);
      const MeshReport report = validate_mesh(mesh[part]);
      CHECK(report.watertight());
      const double expected = part == 0 ? volumes[k].first : volumes[k].second;
      CAPTURE(part);
      CAPTURE(expected);
      CHECK(std::abs(report.enclosed_volume - expected) <= kDeflection * report.surface_area);
    }

    const MeshDistanceIndex i1(mesh[0]), i2(mesh[1]);
    CHECK(deepest_interpenetration(assembled, mesh[0], i1, mesh[1], i2) <= kTouch);
    for (const Eigen::Vector3d& q : seat_points[k]) {
      CAPTURE(q.transpose());
      CHECK(i1.distance(assembled.apply(q)) <= kTouch);
    }
    Pose deeper = assembled;
    deeper.translation.z() -= 0.2;
    CHECK(deepest_interpenetration(deeper, mesh[0], i1, mesh[1], i2) >= 0.15);
  }
}

std::string text_of(const std::string& file) {
  std::ifstream in(file);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST_CASE("real-CAD pairs: scenes/cad and scenes/parts/cad hold what tests/tools/make_cad_pairs writes") {
  namespace fs = std::filesystem;
  const test::TempDir dir;
  const fs::path parts = dir.path / "parts" / "cad", scenes = dir.path / "cad";
  const test::Command made = test::run_command(std::string(SNAPFIT_MAKE_CAD_PAIRS_PATH) + " " + parts.string() + " " +
                                               scenes.string());
  INFO(made.output);
  REQUIRE(made.status == 0);
  const std::string source = SNAPFIT_SOURCE_DIR;
  std::uintmax_t bytes = 0;
  for (const test::CadPairInfo& pair : test::cad_pairs()) {
    CAPTURE(pair.name);
    CHECK(text_of(source + "/scenes/cad/" + pair.name + ".json") == text_of((scenes / (pair.name + ".json")).string()));
    for (const char* part : {"_1.step", "_2.step"}) {
      const std::string shipped = source + "/scenes/parts/cad/" + pair.name + part;
      bytes += fs::file_size(shipped);
      CadImportOptions options;
      options.linear_deflection = 0.06;
      const CadMesh a = load_cad_mesh(shipped, options);
      const CadMesh b = load_cad_mesh((parts / (pair.name + part)).string(), options);
      CHECK(a.facts.solids == b.facts.solids);
      CHECK(a.facts.exact_volume == b.facts.exact_volume);
      CHECK(a.mesh.vertices == b.mesh.vertices);
      CHECK(a.mesh.triangles == b.mesh.triangles);
    }
  }
  CHECK(bytes <= 1024 * 1024);  // small enough to ship
}

}  // namespace
}  // namespace snapfit
