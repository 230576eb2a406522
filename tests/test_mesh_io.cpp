// Mesh import, export and validation (io/mesh_load.h, io/mesh_export.h, mesh/mesh_report.h).
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <unistd.h>
#include <vector>

#include "io/mesh_export.h"
#include "io/mesh_load.h"
#include "mesh/mesh.h"
#include "mesh/mesh_report.h"
#include "snapfit/error.h"

namespace fs = std::filesystem;
using snapfit::Mesh;
using snapfit::MeshReport;

namespace {

// A fresh folder under the system temp directory, removed with everything in it.
struct TempDir {
  fs::path path;
  TempDir() {
    std::random_device rd;
    path = fs::temp_directory_path() / ("snapfit_mesh_io_" + std::to_string(::getpid()) + "_" + std::to_string(rd()));
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::permissions(path, fs::perms::owner_all, fs::perm_options::add, ec);
    fs::remove_all(path, ec);
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
  std::size_t entry_count() const {
    return static_cast<std::size_t>(std::distance(fs::directory_iterator(path), fs::directory_iterator()));
  }
};

void write_text(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// Unit cube [0,1]^3, vertex i at (i&1, (i>>1)&1, (i>>2)&1), outward CCW winding.
Mesh unit_cube() {
  Mesh m;
  for (int i = 0; i < 8; ++i) m.vertices.emplace_back(i & 1, (i >> 1) & 1, (i >> 2) & 1);
  m.triangles = {{0, 2, 3}, {0, 3, 1},   // z = 0
                 {4, 5, 7}, {4, 7, 6},   // z = 1
                 {0, 1, 5}, {0, 5, 4},   // y = 0
                 {2, 6, 7}, {2, 7, 3},   // y = 1
                 {0, 4, 6}, {0, 6, 2},   // x = 0
                 {1, 3, 7}, {1, 7, 5}};  // x = 1
  return m;
}

// Same triangles, every one with its own three vertices (an STL-like soup).
Mesh as_soup(const Mesh& in) {
  Mesh out;
  for (const auto& t : in.triangles) {
    const int base = static_cast<int>(out.vertices.size());
    for (int k = 0; k < 3; ++k) out.vertices.push_back(in.vertices[t[k]]);
    out.triangles.emplace_back(base, base + 1, base + 2);
  }
  return out;
}

// Message of the snapfit::Error thrown by f, or "" when none (a test failure is reported).
template <class F>
std::string error_message(F&& f) {
  try {
    f();
  } catch (const snapfit::Error& e) {
    return e.what();
  } catch (const std::exception& e) {
    FAIL_CHECK("expected snapfit::Error, got another exception: " << e.what());
    return "";
  }
  FAIL_CHECK("expected snapfit::Error, nothing was thrown");
  return "";
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

void check_vec(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol) {
  INFO("got (" << a.transpose() << "), expected (" << b.transpose() << ")");
  CHECK((a - b).cwiseAbs().maxCoeff() <= tol);
}

const fs::path kModels = "/usr/share/assimp/models";

}  // namespace

TEST_CASE("mesh io: unit cube written as binary STL loads back exactly") {
  TempDir dir;
  const std::string path = dir.file("cube.stl");
  snapfit::write_stl(unit_cube(), path);
  CHECK(fs::file_size(path) == 84u + 12u * 50u);  // header + count + 50 bytes per triangle
  CHECK(dir.entry_count() == 1);                  // the temporary was renamed away

  const Mesh m = snapfit::load_mesh(path);
  CHECK(m.triangles.size() == 12);
  const MeshReport r = snapfit::validate_mesh(m);
  CHECK(r.triangle_count == 12);
  CHECK(r.vertex_count == 8);
  CHECK(std::abs(r.enclosed_volume - 1.0) <= 1e-12);
  CHECK(std::abs(r.surface_area - 6.0) <= 1e-12);
  CHECK(r.watertight());
  CHECK(r.degenerate_triangles == 0);
  check_vec(r.bbox_min, Eigen::Vector3d(0, 0, 0), 0.0);
  check_vec(r.bbox_max, Eigen::Vector3d(1, 1, 1), 0.0);

  // The stored normals are the outward unit normals (first record: triangle {0,2,3}, -z).
  std::ifstream in(path, std::ios::binary);
  char header[84];
  in.read(header, 84);
  CHECK(std::string(header, 5) != "solid");  // else readers would take it for ASCII STL
  std::uint32_t count = 0;
  std::memcpy(&count, header + 80, 4);  // little-endian host (x86/ARM)
  CHECK(count == 12);
  float normal[3];
  in.read(reinterpret_cast<char*>(normal), sizeof normal);
  CHECK(normal[0] == 0.0f);
  CHECK(normal[1] == 0.0f);
  CHECK(normal[2] == -1.0f);
}

TEST_CASE("mesh io: scale factor multiplies lengths, areas by s^2, volumes by s^3") {
  TempDir dir;
  const std::string path = dir.file("cube.stl");
  snapfit::write_stl(unit_cube(), path);
  const double s = 2.5;
  const MeshReport r = snapfit::validate_mesh(snapfit::load_mesh(path, s));
  CHECK(std::abs(r.enclosed_volume - s * s * s) <= 1e-12);
  CHECK(std::abs(r.surface_area - 6 * s * s) <= 1e-12);
  check_vec(r.bbox_max, Eigen::Vector3d(s, s, s), 1e-15);

  for (double bad : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()}) {
    const std::string msg = error_message([&] { snapfit::load_mesh(path, bad); });
    CHECK(contains(msg, path));
    CHECK(contains(msg, "scale"));
  }
}

TEST_CASE("mesh io: OBJ written by write_obj round-trips") {
  TempDir dir;
  // A cube rotated and moved off the origin, so coordinates are not small integers.
  Mesh cube = unit_cube();
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (auto& v : cube.vertices) v = rot * (3.0 * v) + Eigen::Vector3d(10.25, -4.5, 0.125);
  const std::string path = dir.file("cube.obj");
  snapfit::write_obj(cube, path);
  CHECK(dir.entry_count() == 1);

  const Mesh m = snapfit::load_mesh(path);
  REQUIRE(m.triangles.size() == cube.triangles.size());
  // Assimp keeps face order and corner order; it stores float32, hence the tolerance.
  for (std::size_t t = 0; t < m.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) check_vec(m.vertices[m.triangles[t][k]], cube.vertices[cube.triangles[t][k]], 1e-5);
  const MeshReport r = snapfit::validate_mesh(m);
  CHECK(r.vertex_count == 8);
  CHECK(r.watertight());
  CHECK(r.enclosed_volume == doctest::Approx(27.0).epsilon(1e-5));
  CHECK(r.surface_area == doctest::Approx(54.0).epsilon(1e-5));

  // Writing again replaces the file atomically and leaves no temporary behind.
  snapfit::write_obj(unit_cube(), path);
  CHECK(dir.entry_count() == 1);
  CHECK(snapfit::validate_mesh(snapfit::load_mesh(path)).enclosed_volume == doctest::Approx(1.0));
}

TEST_CASE("mesh io: node transforms are accumulated, mirrored nodes keep outward normals") {
  TempDir dir;
  // Collada scene: the cube instanced three times (row-major <matrix>):
  //   plain              identity                  -> [0,1]^3,            volume 1
  //   moved > scaled     translate x+10, scale 2   -> [10,12]x[0,2]x[0,2], volume 8
  //   mirrored           x -> -x - 5               -> [-6,-5]x[0,1]x[0,1], volume 1
  const Mesh c = unit_cube();
  std::string pos, idx;
  for (const auto& v : c.vertices)
    pos += std::to_string(v.x()) + " " + std::to_string(v.y()) + " " + std::to_string(v.z()) + " ";
  for (const auto& t : c.triangles)
    idx += std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + " ";
  const std::string dae = R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset><unit name="meter" meter="1"/><up_axis>Y_UP</up_axis></asset>
  <library_geometries>
    <geometry id="cube" name="cube"><mesh>
      <source id="cube-pos">
        <float_array id="cube-pos-array" count="24">)" +
                          pos + R"(</float_array>
        <technique_common><accessor source="#cube-pos-array" count="8" stride="3">
          <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
        </accessor></technique_common>
      </source>
      <vertices id="cube-vtx"><input semantic="POSITION" source="#cube-pos"/></vertices>
      <triangles count="12"><input semantic="VERTEX" source="#cube-vtx" offset="0"/><p>)" +
                          idx + R"(</p></triangles>
    </mesh></geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene">
      <node id="plain"><instance_geometry url="#cube"/></node>
      <node id="moved"><matrix>1 0 0 10 0 1 0 0 0 0 1 0 0 0 0 1</matrix>
        <node id="scaled"><matrix>2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1</matrix><instance_geometry url="#cube"/></node>
      </node>
      <node id="mirrored"><matrix>-1 0 0 -5 0 1 0 0 0 0 1 0 0 0 0 1</matrix><instance_geometry url="#cube"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
  const std::string path = dir.file("three_cubes.dae");
  write_text(path, dae);
  const MeshReport r = snapfit::validate_mesh(snapfit::load_mesh(path));
  CHECK(r.triangle_count == 36);
  CHECK(r.vertex_count == 24);
  CHECK(r.watertight());
  check_vec(r.bbox_min, Eigen::Vector3d(-6, 0, 0), 1e-6);
  check_vec(r.bbox_max, Eigen::Vector3d(12, 2, 2), 1e-6);
  CHECK(r.enclosed_volume == doctest::Approx(10.0).epsilon(1e-9));
}

TEST_CASE("mesh report: closed, open, non-manifold, flipped and degenerate meshes") {
  SUBCASE("closed cube, and the same cube as an unwelded triangle soup") {
    for (const Mesh& m : {unit_cube(), as_soup(unit_cube())}) {
      const MeshReport r = snapfit::validate_mesh(m);
      CHECK(r.vertex_count == 8);  // soup: 36 vertices weld to 8 positions
      CHECK(r.boundary_edges == 0);
      CHECK(r.non_manifold_edges == 0);
      CHECK(r.inconsistent_edges == 0);
      CHECK(r.degenerate_triangles == 0);
      CHECK(r.watertight());
      CHECK(std::abs(r.enclosed_volume - 1.0) <= 1e-12);
      CHECK(std::abs(r.surface_area - 6.0) <= 1e-12);
    }
  }
  SUBCASE("open: one face (two triangles) removed leaves a square hole of 4 edges") {
    Mesh m = unit_cube();
    m.triangles.erase(m.triangles.begin() + 2, m.triangles.begin() + 4);  // z = 1 face
    const MeshReport r = snapfit::validate_mesh(m);
    CHECK(r.boundary_edges == 4);
    CHECK(r.non_manifold_edges == 0);
    CHECK(r.inconsistent_edges == 0);
    CHECK_FALSE(r.watertight());
    CHECK(std::abs(r.surface_area - 5.0) <= 1e-12);
    // Tetrahedra with apex at the origin: each top triangle contributed det/6 = 1/6.
    CHECK(std::abs(r.enclosed_volume - 2.0 / 3.0) <= 1e-12);
  }
  SUBCASE("non-manifold: three triangles on one edge") {
    Mesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
    const MeshReport r = snapfit::validate_mesh(m);
    CHECK(r.non_manifold_edges == 1);  // edge 0-1
    CHECK(r.boundary_edges == 6);      // the other two edges of each triangle
    CHECK(r.inconsistent_edges == 0);  // a non-manifold edge is counted once, as non-manifold
    CHECK_FALSE(r.watertight());
  }
  SUBCASE("one flipped triangle: its three edges are traversed twice the same way") {
    Mesh m = unit_cube();
    std::swap(m.triangles[2][1], m.triangles[2][2]);  // {4,5,7} -> {4,7,5}
    const MeshReport r = snapfit::validate_mesh(m);
    CHECK(r.inconsistent_edges == 3);
    CHECK(r.boundary_edges == 0);
    CHECK(r.non_manifold_edges == 0);
    CHECK_FALSE(r.watertight());
    // det((0,0,1),(1,0,1),(1,1,1))/6 = 1/6 changes sign: V = 1 - 2/6.
    CHECK(std::abs(r.enclosed_volume - 2.0 / 3.0) <= 1e-12);
    CHECK(std::abs(r.surface_area - 6.0) <= 1e-12);
  }
  SUBCASE("all triangles flipped: consistent, watertight, negative volume, warned") {
    Mesh m = unit_cube();
    for (auto& t : m.triangles) std::swap(t[1], t[2]);
    const MeshReport r = snapfit::validate_mesh(m);
    CHECK(r.watertight());
    CHECK(std::abs(r.enclosed_volume + 1.0) <= 1e-12);
    const std::string text = snapfit::format_mesh_report(r);
    CHECK(contains(text, "watertight: yes"));
    CHECK(contains(text, "normals point inward"));
  }
  SUBCASE("degenerate triangles: repeated welded vertex, collinear, tiny") {
    Mesh m;
    m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}, {0, 0, 0}, {0.5, 1e-7, 0}};
    m.triangles = {{0, 1, 2},   // fine, area 1/2
                   {0, 1, 4},   // vertex 4 sits on vertex 0: repeated after welding
                   {0, 1, 3},   // collinear, zero area
                   {0, 1, 5},   // area 5e-8, above the 1e-12 * diag^2 (= 5e-12) threshold
                   {1, 1, 2}};  // repeated index
    MeshReport r = snapfit::validate_mesh(m);
    CHECK(r.degenerate_triangles == 3);
    CHECK(r.vertex_count == 5);
    m.vertices[5] = {0.5, 1e-12, 0};  // area 5e-13: now below the threshold
    r = snapfit::validate_mesh(m);
    CHECK(r.degenerate_triangles == 4);
  }
  SUBCASE("a degenerate triangle added to a closed cube does not open it") {
    Mesh m = unit_cube();
    m.triangles.emplace_back(0, 0, 1);
    const MeshReport r = snapfit::validate_mesh(m);
    CHECK(r.degenerate_triangles == 1);
    CHECK(r.watertight());
    CHECK(std::abs(r.enclosed_volume - 1.0) <= 1e-12);
    CHECK(contains(snapfit::format_mesh_report(r), "degenerate"));
  }
  SUBCASE("out-of-range index is an error, not a crash") {
    Mesh m = unit_cube();
    m.triangles.emplace_back(0, 1, 8);
    CHECK_THROWS_AS(snapfit::validate_mesh(m), snapfit::Error);
  }
}

TEST_CASE("mesh report: text and JSON forms") {
  Mesh m = unit_cube();
  m.triangles.pop_back();
  const MeshReport r = snapfit::validate_mesh(m);
  const std::string text = snapfit::format_mesh_report(r);
  CHECK(contains(text, "watertight: no"));
  CHECK(contains(text, "triangles: 11"));
  CHECK(contains(text, "boundary edges: 3"));
  CHECK_FALSE(contains(text, "normals point inward"));

  const std::string line = snapfit::mesh_report_json(r);
  CHECK(line.find('\n') == std::string::npos);
  const auto j = nlohmann::json::parse(line);
  CHECK(j.at("triangle_count") == 11);
  CHECK(j.at("vertex_count") == 8);
  CHECK(j.at("boundary_edges") == 3);
  CHECK(j.at("non_manifold_edges") == 0);
  CHECK(j.at("inconsistent_edges") == 0);
  CHECK(j.at("degenerate_triangles") == 0);
  CHECK(j.at("watertight") == false);
  CHECK(j.at("surface_area").get<double>() == doctest::Approx(5.5));
  CHECK(j.at("enclosed_volume").get<double>() == doctest::Approx(r.enclosed_volume));
  CHECK(j.at("bbox_max") == nlohmann::json::array({1.0, 1.0, 1.0}));
}

TEST_CASE("mesh io: bad input files throw snapfit::Error naming the file") {
  TempDir dir;
  struct Case {
    std::string name, reason;
  };
  // Each file is created below; `reason` is part of the expected message.
  std::vector<Case> cases = {
      {"missing.stl", "file not found"},
      {"empty.stl", "file is empty"},
      {"garbage.stl", "cannot read mesh"},
      {"truncated.stl", "cannot read mesh"},
      {"points_and_lines.obj", "contains no triangles"},
      {"folder.stl", "not a regular file"},
      {"nan.stl", "non-finite coordinate"},
      {"inf.obj", "non-finite coordinate"},
      {"overflow.obj", "non-finite coordinate"},  // 1e39 does not fit Assimp's float32
      {"huge_counts.off", "OFF header declares"},
  };
  write_text(dir.file("empty.stl"), "");
  std::string garbage;
  for (int i = 0; i < 20; ++i) garbage += "this is not a mesh, only some text\n";
  write_text(dir.file("garbage.stl"), garbage);
  {  // binary STL whose header announces 100 triangles but holds 3
    std::string bin(80, '\0');
    bin.replace(0, 9, "truncated");
    const std::uint32_t n = 100;
    bin.append(reinterpret_cast<const char*>(&n), 4);
    for (int t = 0; t < 3; ++t) bin.append(std::string(50, '\0'));
    write_text(dir.file("truncated.stl"), bin);
  }
  write_text(dir.file("points_and_lines.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1\nl 1 2 3\n");
  fs::create_directory(dir.file("folder.stl"));
  {  // one triangle with a NaN coordinate
    std::string bin(80, 'x');
    const std::uint32_t n = 1;
    bin.append(reinterpret_cast<const char*>(&n), 4);
    const float rec[12] = {0, 0, 1, 0, 0, 0, std::nanf(""), 0, 0, 0, 1, 0};
    bin.append(reinterpret_cast<const char*>(rec), sizeof rec);
    bin.append(2, '\0');
    write_text(dir.file("nan.stl"), bin);
  }
  write_text(dir.file("inf.obj"), "v 0 0 0\nv inf 0 0\nv 0 1 0\nf 1 2 3\n");
  write_text(dir.file("overflow.obj"), "v 0 0 0\nv 1e39 0 0\nv 0 1 0\nf 1 2 3\n");
  // Counts far beyond what the file holds (Assimp would allocate them up front).
  write_text(dir.file("huge_counts.off"), "OFF\n4000000000 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");

  for (const Case& c : cases) {
    const std::string path = dir.file(c.name);
    INFO(c.name);
    const std::string msg = error_message([&] { snapfit::load_mesh(path); });
    INFO("message: " << msg);
    CHECK(msg.rfind(path + ": ", 0) == 0);  // starts with the path
    CHECK(contains(msg, c.reason));
  }
}

TEST_CASE("mesh export: failures name the path and leave no file behind") {
  TempDir dir;
  SUBCASE("folder does not exist") {
    const std::string path = dir.file("no_such_folder/cube.stl");
    const std::string msg = error_message([&] { snapfit::write_stl(unit_cube(), path); });
    CHECK(contains(msg, path));
    CHECK(contains(msg, "No such file or directory"));
    const std::string msg_obj = error_message([&] { snapfit::write_obj(unit_cube(), path); });
    CHECK(contains(msg_obj, path));
  }
  SUBCASE("path is a folder: the rename fails and the temporary is removed") {
    const std::string path = dir.file("taken");
    fs::create_directory(path);
    const std::string msg = error_message([&] { snapfit::write_stl(unit_cube(), path); });
    CHECK(contains(msg, path));
    CHECK(dir.entry_count() == 1);
  }
  SUBCASE("read-only folder") {
    fs::permissions(dir.path, fs::perms::owner_read | fs::perms::owner_exec);
    if (::access(dir.path.c_str(), W_OK) == 0) {
      MESSAGE("running with privileges that ignore folder permissions; skipped");
    } else {
      const std::string path = dir.file("cube.obj");
      const std::string msg = error_message([&] { snapfit::write_obj(unit_cube(), path); });
      CHECK(contains(msg, path));
      CHECK(contains(msg, "Permission denied"));
    }
    fs::permissions(dir.path, fs::perms::owner_all);
    CHECK(dir.entry_count() == 0);
  }
  SUBCASE("invalid mesh") {
    Mesh m = unit_cube();
    m.triangles.emplace_back(0, 1, 99);
    const std::string path = dir.file("bad.stl");
    const std::string msg = error_message([&] { snapfit::write_stl(m, path); });
    CHECK(contains(msg, path));
    m = unit_cube();
    m.vertices[3].x() = std::nan("");
    CHECK(contains(error_message([&] { snapfit::write_obj(m, path); }), path));
    CHECK(dir.entry_count() == 0);
  }
}

TEST_CASE("mesh io: Assimp test models (assimp-testmodels)") {
  if (!fs::is_directory(kModels)) {
    MESSAGE(kModels.string() << " not found (install assimp-testmodels); skipped");
    return;
  }
  const auto report = [](const std::string& rel) {
    INFO(rel);
    return snapfit::validate_mesh(snapfit::load_mesh((kModels / rel).string()));
  };

  SUBCASE("Spider: ASCII and binary STL agree") {
    const MeshReport bin = report("STL/Spider_binary.stl");
    const MeshReport asc = report("STL/Spider_ascii.stl");
    CHECK(bin.triangle_count == 1368);
    CHECK(asc.triangle_count == bin.triangle_count);
    CHECK(asc.vertex_count == bin.vertex_count);  // 722 positions after welding
    check_vec(bin.bbox_min, Eigen::Vector3d(-3.1148949, -4.0, -1.6493286), 1e-6);
    check_vec(bin.bbox_max, Eigen::Vector3d(3.1148949, 4.0, 1.6493286), 1e-6);
    // ASCII decimals and binary float32 differ in the last bits only.
    check_vec(asc.bbox_min, bin.bbox_min, 1e-6);
    check_vec(asc.bbox_max, bin.bbox_max, 1e-6);
    CHECK(asc.enclosed_volume == doctest::Approx(bin.enclosed_volume).epsilon(1e-6));
    // The spider is a set of open, partly flipped, partly degenerate pieces.
    CHECK(bin.boundary_edges == 72);
    CHECK(bin.inconsistent_edges == 10);
    CHECK(bin.degenerate_triangles == 56);
  }

  SUBCASE("Wuson: STL, PLY, OBJ and OFF hold the same surface") {
    const MeshReport stl = report("STL/Wuson.stl");
    const MeshReport ply = report("PLY/Wuson.ply");
    const MeshReport obj = report("OBJ/WusonOBJ.obj");
    const MeshReport off = report("OFF/Wuson.off");
    for (const MeshReport* r : {&stl, &ply, &obj, &off}) {
      CHECK(r->triangle_count == 3732);
      CHECK(r->vertex_count == 2117);
      check_vec(r->bbox_min, Eigen::Vector3d(-0.459976, -0.000566, -1.622242), 1e-6);
      check_vec(r->bbox_max, Eigen::Vector3d(0.459976, 1.515251, 1.622242), 1e-6);
      CHECK(r->surface_area == doctest::Approx(9.0258039).epsilon(1e-6));
      // Not closed: 412 boundary edges, so the "enclosed" volume
      // depends on the origin; the files share coordinates, so they still compare.
      CHECK(r->boundary_edges == 412);
      CHECK(r->non_manifold_edges == 0);
      CHECK(r->inconsistent_edges == 0);
    }
    CHECK(stl.enclosed_volume == doctest::Approx(1.1228033).epsilon(1e-6));
    CHECK(ply.enclosed_volume == doctest::Approx(stl.enclosed_volume).epsilon(0.01));
    CHECK(obj.enclosed_volume == doctest::Approx(stl.enclosed_volume).epsilon(0.01));
    // Wuson.off itself lists every face clockwise (checked on the raw file, without
    // Assimp): same magnitude, opposite sign.
    CHECK(off.enclosed_volume == doctest::Approx(-stl.enclosed_volume).epsilon(0.01));
  }
}

TEST_CASE("mesh io: every file of Assimp's invalid/ folder fails cleanly or loads") {
  const fs::path folder = kModels / "invalid";
  if (!fs::is_directory(folder)) {
    MESSAGE(folder.string() << " not found (install assimp-testmodels); skipped");
    return;
  }
  // Observed with Assimp 5.2.5; the message must start with the path and contain this.
  const std::map<std::string, std::string> expected_error = {
      // Declares 353535235358 vertices in 309 bytes; Assimp would allocate ~16 GB.
      {"OutOfMemory.off", "OFF header declares 353535235358 vertices"},
      {"empty.3ds", "file is empty"},
      {"empty.ase", "file is empty"},
      {"empty.lwo", "file is empty"},
      {"empty.md5mesh", "file is empty"},
      {"empty.obj", "file is empty"},
      {"empty.off", "file is empty"},
      {"empty.ply", "file is empty"},
      {"empty.raw", "file is empty"},
      {"empty.smd", "file is empty"},
      {"empty.x", "file is empty"},
      {"emptyIrrMesh.xml", "cannot read mesh: IRRMESH"},  // every buffer has 0 vertices
      {"malformed.obj", "cannot read mesh: OBJ: Invalid face index"},
      {"readme.txt", "cannot read mesh"},  // no reader for .txt
  };
  std::size_t seen = 0;
  for (const auto& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    const std::string path = entry.path().string();
    INFO(name);
    ++seen;
    if (name == "malformed2.obj") {
      // Loads: the empty "f" line is dropped and the missing material ignored, leaving
      // 5 of the cube's 6 quads: 10 triangles around a 4-edge hole.
      const MeshReport r = snapfit::validate_mesh(snapfit::load_mesh(path));
      CHECK(r.triangle_count == 10);
      CHECK(r.vertex_count == 8);
      CHECK(r.boundary_edges == 4);
      CHECK(r.inconsistent_edges == 0);
      check_vec(r.bbox_min, Eigen::Vector3d(-0.5, -0.5, -0.5), 0.0);
      check_vec(r.bbox_max, Eigen::Vector3d(0.5, 0.5, 0.5), 0.0);
      continue;
    }
    const std::string msg = error_message([&] { snapfit::load_mesh(path); });
    INFO("message: " << msg);
    CHECK(msg.rfind(path + ": ", 0) == 0);
    const auto it = expected_error.find(name);
    if (it != expected_error.end()) CHECK(contains(msg, it->second));
  }
  CHECK(seen == expected_error.size() + 1);
}
