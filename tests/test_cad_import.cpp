// CAD part import (io/cad_load.h): STEP and IGES files that OpenCASCADE writes at test
// time (tests/cad_fixtures.h) against the procedural parts of the same geometry, the
// file's units, solids and names, bad files, the import child, and `snapfit mesh-info`.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <doctest/doctest.h>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "io/cad_load.h"
#include "io/isolated_import.h"
#include "mesh/mesh_report.h"
#include "mesh/procedural/procedural_parts.h"
#include "snapfit/error.h"
#include "tests/cad_fixtures.h"
#include "tests/descriptor_reference.h"
#include "tests/test_support.h"

namespace snapfit {
namespace {

namespace fs = std::filesystem;
using test::kPi;
using test::error_of;

// The default scene's parts (scenes/default.json: a peg of radius 5 and length 30, a
// 30 mm block with a hole 20 deep and a 0.5 mm countersink), with `segments` for the N-gons.
ProceduralPartSpec default_part(int part, int segments) {
  const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  ProceduralPartSpec spec = *(part == 1 ? scene.part1 : scene.part2).procedural;
  spec.numbers["segments"] = segments;
  return spec;
}
ProceduralPartSpec peg_spec(int segments = 64) { return default_part(2, segments); }
ProceduralPartSpec block_spec(int segments = 64) { return default_part(1, segments); }

using test::with_deflection;

// Largest distance from the mesh's vertices and edge midpoints to `surface`, and from
// `surface`'s vertices to the mesh (brute force, tests/descriptor_reference.h).
struct TwoSidedDistance {
  double mesh_to_surface = 0;
  double surface_to_mesh = 0;
};
TwoSidedDistance two_sided_distance(const Mesh& mesh, const Mesh& surface) {
  TwoSidedDistance d;
  std::vector<Eigen::Vector3d> points = mesh.vertices;
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) points.push_back(0.5 * (mesh.vertices[t[k]] + mesh.vertices[t[(k + 1) % 3]]));
  for (const Eigen::Vector3d& p : points)
    d.mesh_to_surface = std::max(d.mesh_to_surface, test::reference_distance(surface, p));
  for (const Eigen::Vector3d& p : surface.vertices)
    d.surface_to_mesh = std::max(d.surface_to_mesh, test::reference_distance(mesh, p));
  return d;
}

Eigen::AlignedBox3d box_of(const Mesh& m) {
  Eigen::AlignedBox3d b;
  for (const Eigen::Vector3d& v : m.vertices) b.extend(v);
  return b;
}

}  // namespace

TEST_CASE("cad import: STEP peg and hole block are watertight and within the deflection of the exact solids") {
  const test::TempDir dir;
  // Reference surfaces: the procedural N-gons at N = 1024 (sagitta r (1 - cos(pi/N)) =
  // 2.4e-5 mm for r = 5; their vertices lie on the exact circles).
  constexpr int kFine = 1024;
  const double fine_sagitta = 5.5 * (1 - std::cos(kPi / kFine));
  for (const double deflection : {0.06, 0.02}) {
    for (const ProceduralPartSpec& spec : {peg_spec(kFine), block_spec(kFine)}) {
      CAPTURE(spec.type);
      CAPTURE(deflection);
      const std::string file = dir.file(spec.type + ".step");
      test::write_cad_part(file, spec);
      const CadMesh cad = load_cad_mesh(file, with_deflection(deflection));
      const MeshReport r = validate_mesh(cad.mesh);
      CHECK(r.watertight());
      CHECK(r.degenerate_triangles == 0);
      CHECK(cad.facts.format == "STEP");
      CHECK(cad.facts.file_unit == "millimetre");
      CHECK(cad.facts.solids.size() == 1);
      CHECK(cad.facts.linear_deflection == deflection);
      CHECK(cad.facts.deflection_source == "given");
      CHECK(cad.facts.triangles == cad.mesh.triangles.size());
      CHECK(cad.facts.faces == (spec.type == "peg" ? 3u : 9u));  // + the hole's wall, countersink and bottom

      // Exact volumes: pi r^2 L; the block minus the hole (cylinder + 45-degree countersink frustum).
      const double exact =
          spec.type == "peg" ? kPi * 25 * 30 : 30.0 * 30 * 30 - kPi * 25 * 19.5 - kPi * 0.5 / 3 * (25 + 27.5 + 30.25);
      CHECK(cad.facts.exact_volume == doctest::Approx(exact).epsilon(1e-9));
      // The mesh lies within `deflection` of the surface, so its volume differs from the
      // exact one by at most area x deflection (inscribed: it is smaller for the peg).
      CHECK(std::abs(r.enclosed_volume - exact) <= cad.facts.exact_area * deflection);

      const Mesh fine = make_procedural_part(spec);
      const TwoSidedDistance d = two_sided_distance(cad.mesh, fine);
      CHECK(d.mesh_to_surface <= deflection + fine_sagitta + 1e-9);
      CHECK(d.surface_to_mesh <= deflection + 1e-9);
      // And the deflection is what sets the tessellation: not much finer than asked.
      CHECK(std::max(d.mesh_to_surface, d.surface_to_mesh) >= 0.25 * deflection);
    }
  }
}

TEST_CASE("cad import: the default deflection is tied to the grid spacing") {
  const test::TempDir dir;
  const std::string file = dir.file("peg.stp");
  test::write_cad_part(file, peg_spec());
  CadImportOptions o;
  o.grid.spacing = 0.6;
  const CadMesh by_spacing = load_cad_mesh(file, o);
  CHECK(by_spacing.facts.linear_deflection == doctest::Approx(kDefaultDeflectionPerSpacing * 0.6).epsilon(1e-15));
  CHECK(by_spacing.facts.angular_deflection_deg == kDefaultAngularDeflectionDeg);
  CHECK(by_spacing.facts.deflection_source.find("grid spacing 0.6") != std::string::npos);
  CHECK(by_spacing.mesh.vertices ==
        load_cad_mesh(file, with_deflection(kDefaultDeflectionPerSpacing * 0.6)).mesh.vertices);
  // A grid given by resolution: its spacing over this solid's box (30 mm tall, 2 mm padding).
  o.grid.spacing.reset();
  o.grid.resolution = 35;
  o.grid.padding = 2;
  const CadMesh by_resolution = load_cad_mesh(file, o);
  CHECK(by_resolution.facts.linear_deflection == doctest::Approx(kDefaultDeflectionPerSpacing * 34.0 / 34));
  // Finer grid, finer mesh.
  o.grid.resolution.reset();
  o.grid.spacing = 0.1;
  CHECK(load_cad_mesh(file, o).mesh.triangles.size() > by_spacing.mesh.triangles.size());
  // A smaller angular deflection refines a coarse tessellation.
  CadImportOptions coarse = with_deflection(1.0);
  const std::size_t coarse_triangles = load_cad_mesh(file, coarse).mesh.triangles.size();
  coarse.angular_deflection_deg = 5;
  CHECK(load_cad_mesh(file, coarse).mesh.triangles.size() > coarse_triangles);
}

TEST_CASE("cad import: an unknown length unit is refused by name, a part far too large says its size") {
  const test::TempDir dir;
  const std::string mm = dir.file("block_mm.step");
  test::write_cad_part(mm, block_spec(), "MM");
  std::ifstream in(mm);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string si = "SI_UNIT(.MILLI.,.METRE.)";
  REQUIRE(text.find(si) != std::string::npos);
  // OpenCASCADE read this as a unit 1000x too large, without a word.
  std::string furlong = text;
  furlong.replace(furlong.find(si), si.size(), "SI_UNIT(.MILLI.,.FURLONG.)");
  test::write_text(dir.file("furlong.step"), furlong);
  const std::string refused = error_of([&] { load_cad_mesh(dir.file("furlong.step"), with_deflection(0.1)); });
  INFO(refused);
  CHECK(refused.find("unknown length unit SI_UNIT(.MILLI.,.FURLONG.)") != std::string::npos);
  // The same part declared in metres is 1000x larger: meshed to a deflection meant for
  // millimetres, the mesher gives up, and the message says how large the part came out.
  std::string metres = text;
  metres.replace(metres.find(si), si.size(), "SI_UNIT($,.METRE.)");
  test::write_text(dir.file("metres.step"), metres);
  const std::string too_fine = error_of([&] { load_cad_mesh(dir.file("metres.step"), with_deflection(0.0005)); });
  INFO(too_fine);
  CHECK(too_fine.find("could not be tessellated") != std::string::npos);
  CHECK(too_fine.find("the solid spans 30000 x 30000 x 30000 mm from the file's length unit metre") !=
        std::string::npos);
  CHECK(too_fine.find("\"scale\"") != std::string::npos);
  // `snapfit mesh-info` says it in the unit it was asked for.
  const test::Command cli = test::run_command(
      std::string(SNAPFIT_CLI_PATH) + " mesh-info " + dir.file("metres.step") + " --units cm --deflection 0.00005");
  INFO(cli.output);
  CHECK(cli.status != 0);
  CHECK(cli.output.find("the solid spans 3000 x 3000 x 3000 cm from the file's length unit metre") != std::string::npos);
}

TEST_CASE("cad import: the file's length unit is converted to the output's") {
  const test::TempDir dir;
  const std::string mm = dir.file("peg_mm.step"), m = dir.file("peg_m.step"), in = dir.file("peg_in.step");
  test::write_cad_part(mm, peg_spec(), "MM");
  test::write_cad_part(m, peg_spec(), "M");
  test::write_cad_part(in, peg_spec(), "INCH");
  const CadMesh a = load_cad_mesh(mm, with_deflection(0.06));
  const CadMesh b = load_cad_mesh(m, with_deflection(0.06));
  const CadMesh c = load_cad_mesh(in, with_deflection(0.06));
  CHECK(a.facts.file_unit == "millimetre");
  CHECK(b.facts.file_unit == "metre");
  CHECK(c.facts.file_unit == "INCH");
  // The same solid: the same tessellation, up to the rounding of the unit conversion
  // (STEP writes 12 significant digits).
  const MeshReport ra = validate_mesh(a.mesh);
  for (const CadMesh* other : {&b, &c}) {
    REQUIRE(other->mesh.vertices.size() == a.mesh.vertices.size());
    CHECK(other->mesh.triangles.size() == a.mesh.triangles.size());
    std::vector<Eigen::Vector3d> p = a.mesh.vertices, q = other->mesh.vertices;
    const auto rounded = [](const Eigen::Vector3d& v) { return (v * 1e6).array().round().eval(); };
    const auto before = [&](const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
      const auto x = rounded(u), y = rounded(v);
      return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
    };
    std::sort(p.begin(), p.end(), before);
    std::sort(q.begin(), q.end(), before);
    double worst = 0;
    for (std::size_t i = 0; i < p.size(); ++i) worst = std::max(worst, (p[i] - q[i]).norm());
    CHECK(worst <= 1e-9);
    const MeshReport r = validate_mesh(other->mesh);
    CHECK(r.watertight());
    CHECK(r.enclosed_volume == doctest::Approx(ra.enclosed_volume).epsilon(1e-10));
    CHECK(other->facts.exact_volume == doctest::Approx(a.facts.exact_volume).epsilon(1e-10));
  }
  // Output in metres, times a scale: coordinates 1e-3 x 2 of the millimetre ones; the
  // deflection is in output units.
  CadImportOptions metres = with_deflection(0.06e-3 * 2);
  metres.metres_per_unit = 1.0;
  metres.scale = 2;
  const CadMesh d = load_cad_mesh(in, metres);
  REQUIRE(d.mesh.vertices.size() == c.mesh.vertices.size());
  for (std::size_t i = 0; i < c.mesh.vertices.size(); ++i)
    CHECK((d.mesh.vertices[i] - 2e-3 * c.mesh.vertices[i]).norm() <= 1e-15);
  CHECK(d.facts.exact_volume == doctest::Approx(a.facts.exact_volume * 8e-9).epsilon(1e-12));
}

TEST_CASE("cad import: IGES faces are sewn into the solid") {
  const test::TempDir dir;
  for (const ProceduralPartSpec& spec : {peg_spec(), block_spec()}) {
    CAPTURE(spec.type);
    const std::string iges = dir.file(spec.type + ".igs"), step = dir.file(spec.type + ".step");
    test::write_cad_part(iges, spec, "INCH");
    test::write_cad_part(step, spec);
    const CadMesh a = load_cad_mesh(iges, with_deflection(0.06));
    const CadMesh b = load_cad_mesh(step, with_deflection(0.06));
    CHECK(a.facts.format == "IGES");
    CHECK(a.facts.file_unit == "INCH");
    CHECK(a.facts.solids == std::vector<std::string>{"solid 1"});
    const MeshReport r = validate_mesh(a.mesh);
    CHECK(r.watertight());
    CHECK(r.enclosed_volume > 0);  // outward normals
    // IGES has no cylinders or cones (surfaces of revolution instead), so the two files
    // tessellate differently; both lie within the deflection of the exact solid.
    CHECK(a.facts.exact_volume == doctest::Approx(b.facts.exact_volume).epsilon(1e-6));
    CHECK(std::abs(r.enclosed_volume - b.facts.exact_volume) <= b.facts.exact_area * 0.06);
    CHECK((box_of(a.mesh).min() - box_of(b.mesh).min()).cwiseAbs().maxCoeff() <= 0.06);
    CHECK((box_of(a.mesh).max() - box_of(b.mesh).max()).cwiseAbs().maxCoeff() <= 0.06);
  }
}

TEST_CASE("cad import: a file with several solids is refused with their names unless one is named") {
  const test::TempDir dir;
  const std::string named = dir.file("named.step");
  test::write_cad_boxes(named, {{"base", {0, 0, 0}, {10, 10, 2}}, {"lid", {0, 0, 5}, {10, 10, 6}}});
  const std::string msg = error_of([&] { load_cad_mesh(named, with_deflection(0.1)); });
  CHECK(msg.find(named + ": holds 2 solids ('base', 'lid'); name the one to use") == 0);
  // The library names the request member; the tool says its option.
  CHECK(msg.find("(a scene part's cad.solid, MeshFileRequest::solid)") != std::string::npos);
  CHECK(msg.find("--") == std::string::npos);
  const test::Command tool = test::run_command(std::string(SNAPFIT_CLI_PATH) + " mesh-info " + named);
  CHECK(tool.status != 0);
  CHECK(tool.output.find("(a scene part's cad.solid, mesh-info's --solid)") != std::string::npos);
  CadImportOptions o = with_deflection(0.1);
  o.solid = "lid";
  const CadMesh lid = load_cad_mesh(named, o);
  CHECK(lid.facts.solid == "lid");
  CHECK(lid.facts.solids == std::vector<std::string>{"base", "lid"});
  CHECK(lid.facts.faces == 6);
  CHECK(box_of(lid.mesh).min().isApprox(Eigen::Vector3d(0, 0, 5)));
  CHECK(box_of(lid.mesh).max().isApprox(Eigen::Vector3d(10, 10, 6)));
  CHECK(validate_mesh(lid.mesh).enclosed_volume == doctest::Approx(100));
  o.solid = "cover";
  CHECK(error_of([&] { load_cad_mesh(named, o); }) ==
        named + ": no solid named 'cover' (the file's solids: 'base', 'lid')");

  // Unnamed solids take their product's name; without one they are numbered; repeated
  // names are numbered too.
  const std::string unnamed = dir.file("unnamed.step"), repeated = dir.file("repeated.step");
  const std::string product = dir.file("product.step");
  test::write_cad_boxes(product, {{"", {0, 0, 0}, {1, 1, 1}}, {"", {2, 0, 0}, {3, 1, 1}}}, "plate");
  CHECK(error_of([&] {
          load_cad_mesh(product, with_deflection(0.1));
        }).find("holds 2 solids ('plate [1]', 'plate [2]')") != std::string::npos);
  test::write_cad_boxes(unnamed, {{"", {0, 0, 0}, {1, 1, 1}}, {"", {2, 0, 0}, {3, 1, 1}}, {"", {4, 0, 0}, {5, 1, 1}}});
  test::write_cad_boxes(repeated, {{"pin", {0, 0, 0}, {1, 1, 1}}, {"pin", {2, 0, 0}, {3, 1, 1}}});
  CHECK(error_of([&] {
          load_cad_mesh(unnamed, with_deflection(0.1));
        }).find("holds 3 solids ('solid 1', 'solid 2', 'solid 3')") != std::string::npos);
  CHECK(error_of([&] {
          load_cad_mesh(repeated, with_deflection(0.1));
        }).find("holds 2 solids ('pin [1]', 'pin [2]')") != std::string::npos);
  o.solid = "pin [2]";
  CHECK(box_of(load_cad_mesh(repeated, o).mesh).min().isApprox(Eigen::Vector3d(2, 0, 0)));

  // Two placements of one solid (an assembly's instances): both carry its name.
  const std::string instances = dir.file("instances.step");
  test::write_cad_instances(instances, {"bolt", {0, 0, 0}, {1, 2, 3}}, 10);
  o.solid = "bolt [2]";
  const CadMesh second = load_cad_mesh(instances, o);
  CHECK(second.facts.solids == std::vector<std::string>{"bolt [1]", "bolt [2]"});
  CHECK(box_of(second.mesh).min().isApprox(Eigen::Vector3d(10, 0, 0)));
  CHECK(box_of(second.mesh).max().isApprox(Eigen::Vector3d(11, 2, 3)));
}

TEST_CASE("cad import: truncated, empty, non-STEP and solid-less files are errors naming the file") {
  const test::TempDir dir;
  const std::string good = dir.file("good.step");
  test::write_cad_part(good, block_spec());
  const std::vector<char> bytes = test::read_bytes(good);
  const auto expect_error = [&](const std::string& file, const std::string& part) {
    const std::string msg = error_of([&] { load_cad_mesh(file, with_deflection(0.1)); });
    INFO("message: ", msg);
    CHECK(msg.rfind(file + ": ", 0) == 0);
    CHECK(msg.find(part) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
  };
  // Cut at a few places: inside the header, inside the data section, just before its end.
  for (const double fraction : {0.01, 0.3, 0.6, 0.95}) {
    CAPTURE(fraction);
    const std::string cut = dir.file("cut.step");
    test::write_bytes(cut,
                      std::vector<char>(bytes.begin(), bytes.begin() + static_cast<long>(fraction * bytes.size())));
    expect_error(cut, fraction < 0.02 ? "cannot read CAD file: " : "cannot read CAD file: truncated STEP file");
  }
  const std::string cut_iges = dir.file("cut.igs");
  test::write_cad_part(cut_iges, block_spec());
  const std::vector<char> iges = test::read_bytes(cut_iges);
  test::write_bytes(cut_iges, std::vector<char>(iges.begin(), iges.begin() + static_cast<long>(iges.size() / 2)));
  expect_error(cut_iges, "cannot read CAD file: truncated or not an IGES file");
  const std::string empty = dir.file("empty.step");
  test::write_bytes(empty, {});
  expect_error(empty, "file is empty");
  const std::string stl = dir.file("stl.step");
  test::write_text(stl,
                   "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\n"
                   "endfacet\nendsolid x\n");
  expect_error(stl, "cannot read CAD file: not a STEP file");
  // Opening and closing lines right, the entities between them not STEP.
  const std::string garbled = dir.file("garbled.step");
  test::write_text(garbled,
                   "ISO-10303-21;\nHEADER;\nthis is ( not STEP\nENDSEC;\nDATA;\n#1=(;\nENDSEC;\nEND-ISO-10303-21;\n");
  expect_error(garbled, "cannot read CAD file: ");
  const std::string noise = dir.file("noise.igs");
  std::vector<char> random(5000);
  for (std::size_t i = 0; i < random.size(); ++i) random[i] = static_cast<char>((i * 2654435761u) >> 13);
  test::write_bytes(noise, random);
  expect_error(noise, "cannot read CAD file: ");
  expect_error(dir.file("missing.stp"), "file not found");
  // A valid STEP file without any shape: only its header and an empty data section.
  const std::string header_only = dir.file("header.step");
  const std::string text(bytes.begin(), bytes.end());
  test::write_text(header_only, text.substr(0, text.find("DATA;")) + "DATA;\nENDSEC;\nEND-ISO-10303-21;\n");
  expect_error(header_only, "cannot read CAD file: ");
  // A file name that is neither STEP nor IGES, and bad options.
  expect_error(dir.file("part.stl"), "not a STEP or IGES file name");
  CadImportOptions o;
  CHECK(error_of([&] { load_cad_mesh(good, o); }).find("needs a linear deflection, or a grid spacing") !=
        std::string::npos);
  o.linear_deflection = -1;
  CHECK(error_of([&] { load_cad_mesh(good, o); }) == good + ": the linear deflection must be finite and > 0 (got -1)");
  o.linear_deflection = 0.1;
  o.angular_deflection_deg = 0;
  CHECK(error_of([&] { load_cad_mesh(good, o); }).find("angular deflection must be in (0, 90]") != std::string::npos);
}

TEST_CASE("cad import: the import child starts no threads and the parent process never loads the file") {
  const test::TempDir dir;
  const std::string file = dir.file("block.step");
  test::write_cad_part(file, block_spec());
  // The whole import in a child of its own (as load_cad_mesh's child does it), then the
  // number of threads that child has: OpenCASCADE must not have started any.
  const test::EnvScope in_process("SNAPFIT_IMPORT_MEMORY_MIB", "inprocess");
  const ChildResult r = run_in_child(
      [&] {
        const CadMesh m = load_cad_mesh(file, with_deflection(0.02));
        std::size_t threads = 0;
        for ([[maybe_unused]] const auto& task : fs::directory_iterator("/proc/self/task")) ++threads;
        return std::to_string(threads) + " " + std::to_string(m.mesh.triangles.size());
      },
      ChildLimits{1024, 60, 180});
  REQUIRE(r.status == ChildResult::Status::ok);
  CHECK(r.bytes.substr(0, r.bytes.find(' ')) == "1");
  // In this process (inprocess) and through the child (default) the mesh is the same.
  const CadMesh here = load_cad_mesh(file, with_deflection(0.02));
  CHECK(r.bytes.substr(r.bytes.find(' ') + 1) == std::to_string(here.mesh.triangles.size()));
  const test::EnvScope child("SNAPFIT_IMPORT_MEMORY_MIB", nullptr);
  const CadMesh there = load_cad_mesh(file, with_deflection(0.02));
  CHECK(there.mesh.vertices == here.mesh.vertices);
  CHECK(there.mesh.triangles == here.mesh.triangles);
  // A memory limit the reader cannot work in is an error naming the file, not a crash.
  const test::EnvScope tiny("SNAPFIT_IMPORT_MEMORY_MIB", "1");
  const std::string refused = error_of([&] { load_cad_mesh(file, with_deflection(0.02)); });
  INFO(refused);
  CHECK(refused.rfind(file + ": cannot read CAD file: ", 0) == 0);
}

TEST_CASE("cad import: snapfit mesh-info reports the mesh and the CAD facts") {
  const test::TempDir dir;
  const std::string file = dir.file("peg.step");
  test::write_cad_part(file, peg_spec(), "INCH", "peg");
  const test::Command json = test::run_command(
      std::string(SNAPFIT_CLI_PATH) + " mesh-info " + file + " --json --spacing 0.6 --units cm", false);
  REQUIRE(json.status == 0);
  const nlohmann::json j = nlohmann::json::parse(json.output);
  CHECK(j["watertight"] == true);
  CHECK(j["cad"]["format"] == "STEP");
  CHECK(j["cad"]["file_unit"] == "INCH");
  CHECK(j["cad"]["solids"] == nlohmann::json::array({"peg"}));
  CHECK(j["cad"]["faces"] == 3);
  CHECK(j["cad"]["linear_deflection"].get<double>() == doctest::Approx(kDefaultDeflectionPerSpacing * 0.6));
  CHECK(j["cad"]["triangles"] == j["triangle_count"]);
  CHECK(j["bbox_max"][2].get<double>() == doctest::Approx(3.0));  // 30 mm in cm
  CHECK(j["cad"]["exact_volume"].get<double>() == doctest::Approx(kPi * 0.25 * 3.0).epsilon(1e-9));

  const test::Command text = test::run_command(std::string(SNAPFIT_CLI_PATH) + " mesh-info " + file, false);
  REQUIRE(text.status == 0);
  CHECK(text.output.find("cad solids: 1 ('peg')") != std::string::npos);
  CHECK(text.output.find("cad linear deflection: ") != std::string::npos);
  CHECK(text.output.find("0.025 x grid spacing") != std::string::npos);
  CHECK(text.output.find("watertight: yes") != std::string::npos);

  const std::string cut = dir.file("cut.step");
  const std::vector<char> bytes = test::read_bytes(file);
  test::write_bytes(cut, std::vector<char>(bytes.begin(), bytes.begin() + static_cast<long>(bytes.size() / 2)));
  const test::Command bad = test::run_command(std::string(SNAPFIT_CLI_PATH) + " mesh-info " + cut);
  CHECK(bad.status != 0);
  CHECK(bad.output.find("snapfit: error: " + cut + ": cannot read CAD file: ") != std::string::npos);
  const test::Command unit = test::run_command(std::string(SNAPFIT_CLI_PATH) + " mesh-info " + file + " --units ft");
  CHECK(unit.status != 0);
  CHECK(unit.output.find("--units: unknown unit 'ft'") != std::string::npos);
}

TEST_CASE("cad import: scenes/parts holds what tests/tools/make_cad_parts writes for the default scene") {
  const test::TempDir dir;
  const test::Command made = test::run_command(std::string(SNAPFIT_MAKE_CAD_PARTS_PATH) + " " + SNAPFIT_SOURCE_DIR +
                                               "/scenes/default.json " + dir.path.string());
  INFO(made.output);
  REQUIRE(made.status == 0);
  for (const char* name : {"peg.step", "hole_block.step"}) {
    CAPTURE(name);
    const std::string shipped = std::string(SNAPFIT_SOURCE_DIR) + "/scenes/parts/" + name;
    CHECK(fs::file_size(shipped) <= 64 * 1024);  // small enough to ship
    const CadMesh a = load_cad_mesh(shipped, with_deflection(0.06));
    const CadMesh b = load_cad_mesh(dir.file(name), with_deflection(0.06));
    CHECK(a.facts.solids == b.facts.solids);
    CHECK(a.facts.file_unit == b.facts.file_unit);
    CHECK(a.facts.exact_volume == b.facts.exact_volume);
    CHECK(a.mesh.vertices == b.mesh.vertices);
    CHECK(a.mesh.triangles == b.mesh.triangles);
  }
}

}  // namespace snapfit
