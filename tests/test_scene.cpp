// Scene files (snapfit/scene.h): the shipped scenes, round trips, and one check per error class.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <unistd.h>

#include "snapfit/error.h"
#include "snapfit/scene.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace snapfit;

namespace {

// A small valid scene; tests change one thing and check the message.
json base_scene() {
  return json::parse(R"({
    "snapfit_scene": 1,
    "name": "test",
    "units": "mm",
    "part1": {"name": "block", "procedural": {"type": "hole_block", "peg_radius": 5, "clearance": 0,
              "hole_depth": 20, "width": 30, "height": 30, "chamfer": 0.5, "segments": 64}},
    "part2": {"name": "peg", "procedural": {"type": "peg", "radius": 5, "length": 30},
              "pose": {"position": [1, 0, 10], "rotation": {"axis": [0, 1, 0], "angle_deg": 3}}},
    "assembled_pose": {"position": [0, 0, -20]},
    "descriptor": {"kind": "skeletal_density", "sigma": 0.5, "lambda_in": 3, "lambda_out": 1, "tolerance": 1e-3},
    "grid": {"spacing": 0.6, "padding": 5},
    "frame": {"budget_ms": 1.0, "rate_hz": 1000},
    "outputs": ["energy", "force", "torque"],
    "motion": "6dof",
    "trajectory": {"keyframes": [
      {"time_s": 0, "position": [1, 0, 10], "rotation": {"axis": [0, 1, 0], "angle_deg": 3}},
      {"time_s": 2, "position": [0, 0, -20]}]}
  })");
}

// The message parse_scene throws for `text`, or "" when it parses.
std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "test.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}
std::string error_of(const char* text) { return error_of(std::string(text)); }
std::string error_of(const json& j) { return error_of(j.dump()); }

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Expects an error whose message contains `part` (and so names the file and field).
#define CHECK_ERROR(scene, part)              \
  do {                                        \
    const std::string msg_ = error_of(scene); \
    INFO("message: ", msg_);                  \
    CHECK(contains(msg_, "test.json: "));     \
    CHECK(contains(msg_, part));              \
  } while (0)

// A fresh empty folder under the temp directory, removed at scope exit.
struct TempDir {
  fs::path path;
  explicit TempDir(const std::string& tag) {
    path = fs::temp_directory_path() / ("snapfit_test_scene_" + tag + "_" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

void write_text(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p) << text;
}

bool same_pose(const Pose& a, const Pose& b) {
  return a.rotation.coeffs() == b.rotation.coeffs() && a.translation == b.translation;
}
bool same_part(const PartSpec& a, const PartSpec& b) {
  const bool same_proc =
      a.procedural.has_value() == b.procedural.has_value() &&
      (!a.procedural || (a.procedural->type == b.procedural->type && a.procedural->numbers == b.procedural->numbers &&
                         a.procedural->arrays == b.procedural->arrays));
  const bool same_cad = a.cad.solid == b.cad.solid && a.cad.deflection == b.cad.deflection &&
                        a.cad.angular_deflection_deg == b.cad.angular_deflection_deg;
  return a.name == b.name && a.mesh_path == b.mesh_path && a.mesh_scale == b.mesh_scale && same_proc && same_cad &&
         same_pose(a.pose, b.pose);
}
// Field-by-field equality, source_path aside.
void check_same_scene(const Scene& a, const Scene& b) {
  CHECK(a.name == b.name);
  CHECK(a.units == b.units);
  CHECK(same_part(a.part1, b.part1));
  CHECK(same_part(a.part2, b.part2));
  CHECK(a.assembled_pose.has_value() == b.assembled_pose.has_value());
  if (a.assembled_pose && b.assembled_pose) CHECK(same_pose(*a.assembled_pose, *b.assembled_pose));
  CHECK(a.descriptor.kind == b.descriptor.kind);
  CHECK(a.descriptor.sigma == b.descriptor.sigma);
  CHECK(a.descriptor.lambda_in == b.descriptor.lambda_in);
  CHECK(a.descriptor.lambda_out == b.descriptor.lambda_out);
  CHECK(a.descriptor.tolerance == b.descriptor.tolerance);
  CHECK(a.grid.spacing == b.grid.spacing);
  CHECK(a.grid.resolution == b.grid.resolution);
  CHECK(a.grid.padding == b.grid.padding);
  CHECK(a.frame_budget_ms == b.frame_budget_ms);
  CHECK(a.loop_rate_hz == b.loop_rate_hz);
  CHECK(a.outputs.energy == b.outputs.energy);
  CHECK(a.outputs.force == b.outputs.force);
  CHECK(a.outputs.torque == b.outputs.torque);
  CHECK(a.motion == b.motion);
  REQUIRE(a.trajectory.keyframes.size() == b.trajectory.keyframes.size());
  for (size_t i = 0; i < a.trajectory.keyframes.size(); ++i) {
    CHECK(a.trajectory.keyframes[i].time_s == b.trajectory.keyframes[i].time_s);
    CHECK(same_pose(a.trajectory.keyframes[i].pose, b.trajectory.keyframes[i].pose));
  }
  const HapticsParams &ha = a.haptics, &hb = b.haptics;
  CHECK(ha.mass_kg == hb.mass_kg);
  CHECK(ha.stiffness_n_per_m == hb.stiffness_n_per_m);
  CHECK(ha.rot_stiffness_nm_per_rad == hb.rot_stiffness_nm_per_rad);
  CHECK(ha.damping_ratio == hb.damping_ratio);
  CHECK(ha.max_force_n == hb.max_force_n);
  CHECK(ha.max_torque_nm == hb.max_torque_nm);
  CHECK(ha.geometry_gain == hb.geometry_gain);
  CHECK(ha.geometry_strength == hb.geometry_strength);
  CHECK(ha.settle_s == hb.settle_s);
  CHECK(ha.success_position == hb.success_position);
  CHECK(ha.success_angle_deg == hb.success_angle_deg);
  CHECK(a.method == b.method);
  CHECK(a.vps.voxel_size == b.vps.voxel_size);
  CHECK(a.vps.stiffness_n_per_m == b.vps.stiffness_n_per_m);
  CHECK(a.vps.shell_density == b.vps.shell_density);
  CHECK(a.vps.proximity_layers == b.vps.proximity_layers);
  CHECK(a.vps.braking_n_s_per_m == b.vps.braking_n_s_per_m);
  const VpsHybridParams &ya = a.vps.hybrid, &yb = b.vps.hybrid;
  CHECK(ya.alignment_fraction == yb.alignment_fraction);
  CHECK(ya.rotation_fraction == yb.rotation_fraction);
  CHECK(ya.x_engage == yb.x_engage);
  CHECK(ya.x_release == yb.x_release);
  CHECK(ya.x_full == yb.x_full);
  CHECK(ya.ramp_s == yb.ramp_s);
  CHECK(ya.radius_tolerance == yb.radius_tolerance);
  CHECK(ya.offset_tolerance == yb.offset_tolerance);
  CHECK(ya.angle_tolerance_deg == yb.angle_tolerance_deg);
  CHECK(ya.region == yb.region);
}

std::vector<fs::path> shipped_scenes() {
  std::vector<fs::path> out;
  for (const auto& entry : fs::directory_iterator(fs::path(SNAPFIT_SOURCE_DIR) / "scenes"))
    if (entry.path().extension() == ".json") out.push_back(entry.path());
  std::sort(out.begin(), out.end());
  return out;
}

}  // namespace

TEST_CASE("scene: haptics fields round-trip and unknown ones are refused") {
  json j = base_scene();
  j["haptics"] = {{"mass_kg", 0.2},        {"stiffness_n_per_m", 1500}, {"rot_stiffness_nm_per_rad", 0.3},
                  {"damping_ratio", 0.7},  {"max_force_n", 3.3},        {"max_torque_nm", 0},
                  {"geometry_gain", 2e-4}, {"settle_s", 0.5},           {"success_position", 0.25},
                  {"success_angle_deg", 2}};
  const Scene s = parse_scene(j.dump(), "test.json");
  CHECK(s.haptics.mass_kg == 0.2);
  CHECK(s.haptics.rot_stiffness_nm_per_rad == 0.3);
  CHECK(s.haptics.max_torque_nm == 0);
  CHECK(s.haptics.geometry_gain == 2e-4);
  CHECK(s.haptics.success_position == 0.25);
  check_same_scene(s, parse_scene(scene_to_json(s), "copy.json"));
  j["haptics"]["stifness_n_per_m"] = 1;
  CHECK_ERROR(j, "test.json: haptics.stifness_n_per_m: unknown field");
  const Scene d = parse_scene(base_scene().dump(), "test.json");
  CHECK(d.haptics.mass_kg == 0.05);
  CHECK(!d.haptics.geometry_gain);
  CHECK(!d.haptics.success_position);
}

TEST_CASE("scene: method and vps fields round-trip, and bad ones are named") {
  const Scene d = parse_scene(base_scene().dump(), "test.json");
  CHECK(d.method == Method::snapfit);
  CHECK(!d.vps.voxel_size);
  json j = base_scene();
  j["method"] = "vps";
  j["vps"] = {{"voxel_size", 0.25},
              {"stiffness_n_per_m", 500},
              {"shell_density", 2},
              {"proximity_layers", 3},
              {"braking_n_s_per_m", 0.5}};
  const Scene s = parse_scene(j.dump(), "test.json");
  CHECK(s.method == Method::vps);
  CHECK(s.vps.voxel_size == 0.25);
  CHECK(s.vps.stiffness_n_per_m == 500);
  CHECK(s.vps.shell_density == 2);
  CHECK(s.vps.proximity_layers == 3);
  CHECK(s.vps.braking_n_s_per_m == 0.5);
  check_same_scene(s, parse_scene(scene_to_json(s), "copy.json"));

  const auto with = [&](const std::string& field, const json& value) {
    json k = j;
    k["vps"][field] = value;
    return k;
  };
  json bad = j;
  bad["method"] = "voxels";
  CHECK_ERROR(bad, "test.json: method: unknown method 'voxels' (expected snapfit, vps or vps_hybrid)");
  bad["method"] = 1;
  CHECK_ERROR(bad, "method: expected a string");
  CHECK_ERROR(with("voxel_size", -1), "vps.voxel_size: must be > 0");
  CHECK_ERROR(with("voxel_size", "fine"), "vps.voxel_size: expected a number");
  CHECK_ERROR(with("stiffness_n_per_m", 0), "vps.stiffness_n_per_m: must be > 0");
  CHECK_ERROR(with("shell_density", 20), "vps.shell_density: must be in (0, 8] (got 20)");
  CHECK_ERROR(with("proximity_layers", 1.5), "vps.proximity_layers: must be an integer in [0, 16] (got 1.5)");
  CHECK_ERROR(with("braking_n_s_per_m", -2), "vps.braking_n_s_per_m: must be >= 0");
  CHECK_ERROR(with("density", 2), "vps.density: unknown field");
}

TEST_CASE("scene: vps.hybrid fields round-trip, and bad ones are named") {
  const Scene d = parse_scene(base_scene().dump(), "test.json");
  CHECK(d.vps.hybrid.alignment_fraction == 0.5);  // docs/scenes.md's defaults
  CHECK(d.vps.hybrid.rotation_fraction == 0.9);
  CHECK(d.vps.hybrid.x_full == 0.8);
  CHECK(d.vps.hybrid.region == HybridRegion::face);
  CHECK(!d.vps.hybrid.radius_tolerance);
  json j = base_scene();
  j["method"] = "vps_hybrid";
  j["vps"] = {{"voxel_size", 0.5},
              {"hybrid",
               {{"alignment_fraction", 0.4},
                {"rotation_fraction", 0.8},
                {"x_engage", 0.7},
                {"x_release", 0.5},
                {"x_full", 0.9},
                {"ramp_s", 0.02},
                {"radius_tolerance", 1.5},
                {"offset_tolerance", 0.75},
                {"angle_tolerance_deg", 5},
                {"region", "pair"}}}};
  const Scene s = parse_scene(j.dump(), "test.json");
  const VpsHybridParams& h = s.vps.hybrid;
  CHECK(h.alignment_fraction == 0.4);
  CHECK(h.rotation_fraction == 0.8);
  CHECK(h.x_engage == 0.7);
  CHECK(h.x_release == 0.5);
  CHECK(h.x_full == 0.9);
  CHECK(h.ramp_s == 0.02);
  CHECK(h.radius_tolerance == 1.5);
  CHECK(h.offset_tolerance == 0.75);
  CHECK(h.angle_tolerance_deg == 5);
  CHECK(h.region == HybridRegion::pair);
  check_same_scene(s, parse_scene(scene_to_json(s), "copy.json"));

  const auto with = [&](const std::string& field, const json& value) {
    json k = j;
    k["vps"]["hybrid"][field] = value;
    return k;
  };
  CHECK_ERROR(with("alignment_fraction", 1),
              "test.json: vps.hybrid.alignment_fraction: must be in (0, 1): the user stays stronger than the "
              "constraint (got 1)");
  CHECK_ERROR(with("rotation_fraction", 0), "vps.hybrid.rotation_fraction: must be in (0, 1)");
  CHECK_ERROR(with("x_engage", 1.2), "vps.hybrid.x_engage: must be in (0, 1] (got 1.2)");
  CHECK_ERROR(with("x_full", 0), "vps.hybrid.x_full: must be in (0, 1] (got 0)");
  CHECK_ERROR(with("x_release", 0.8), "vps.hybrid.x_release: must be below x_engage (got 0.8 against 0.7)");
  CHECK_ERROR(with("ramp_s", -1), "vps.hybrid.ramp_s: must be >= 0 (got -1)");
  CHECK_ERROR(with("radius_tolerance", 0), "vps.hybrid.radius_tolerance: must be > 0 (got 0)");
  CHECK_ERROR(with("offset_tolerance", "wide"), "vps.hybrid.offset_tolerance: expected a number, got string");
  CHECK_ERROR(with("angle_tolerance_deg", 120), "vps.hybrid.angle_tolerance_deg: must be in (0, 90] (got 120)");
  CHECK_ERROR(with("region", "all"), "vps.hybrid.region: unknown region 'all' (expected pair or face)");
  CHECK_ERROR(with("x_ful", 1), "vps.hybrid.x_ful: unknown field");
  json not_object = j;
  not_object["vps"]["hybrid"] = 3;
  CHECK_ERROR(not_object, "vps.hybrid");
}

TEST_CASE("scene: every shipped scene parses and round-trips") {
  const auto files = shipped_scenes();
  CHECK(files.size() >= 5);
  TempDir dir("shipped");
  for (const fs::path& file : files) {
    INFO("scene file: ", file.string());
    Scene s;
    try {
      s = load_scene(file.string());
    } catch (const Error& e) {
      FAIL_CHECK(e.what());
      continue;
    }
    CHECK(!s.name.empty());
    CHECK(s.source_path == file.string());
    CHECK(!s.trajectory.keyframes.empty());
    const fs::path copy = dir.path / file.filename();
    write_text(copy, scene_to_json(s));
    check_same_scene(s, load_scene(copy.string()));
  }
}

TEST_CASE("scene: the default scene holds what it says") {
  const Scene s = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  REQUIRE(s.part1.procedural);
  CHECK(s.part1.procedural->type == "hole_block");
  CHECK(s.part1.procedural->numbers.at("clearance") == 0);
  CHECK(s.part1.procedural->numbers.at("chamfer") == 0.5);
  CHECK(s.part1.procedural->numbers.at("peg_radius") == 5);
  CHECK(s.motion == Motion::six_dof);
  CHECK((s.outputs.energy && s.outputs.force && s.outputs.torque));
  CHECK(s.descriptor.sigma == 0.5);
  CHECK(s.descriptor.lambda_in / s.descriptor.lambda_out == 3);
  REQUIRE(s.assembled_pose);
  CHECK(s.assembled_pose->translation.isApprox(Eigen::Vector3d(0, 0, -20)));
  REQUIRE(s.trajectory.keyframes.size() >= 4);
  // Ends at the inserted pose.
  CHECK(same_pose(s.trajectory.keyframes.back().pose, *s.assembled_pose));
}

TEST_CASE("scene: round trip of a scene with a mesh part and defaults") {
  TempDir dir("roundtrip");
  write_text(dir.path / "meshes" / "peg.stl", "solid x\nendsolid x\n");
  json j = base_scene();
  j["part2"] = json::parse(R"({"mesh": "meshes/peg.stl", "mesh_units": "m", "scale": 2,
                               "pose": {"rotation": {"quaternion": [0.5, 0.5, 0.5, 0.5]}}})");
  j["grid"] = json::parse(R"({"resolution": 96})");
  j.erase("descriptor");
  j.erase("frame");
  write_text(dir.path / "a.json", j.dump());
  const Scene a = load_scene((dir.path / "a.json").string());
  CHECK(a.part2.name == "part2");
  write_text(dir.path / "elsewhere" / "b.json", scene_to_json(a));
  const Scene b = load_scene((dir.path / "elsewhere" / "b.json").string());
  check_same_scene(a, b);
  CHECK(b.part2.mesh_path == a.part2.mesh_path);  // written absolute, so the folder does not matter
  CHECK(scene_to_json(a) == scene_to_json(b));
}

TEST_CASE("scene: defaults for optional fields") {
  json j = base_scene();
  for (const char* key : {"name", "assembled_pose", "descriptor", "frame", "outputs", "motion", "trajectory"})
    j.erase(key);
  j["part1"].erase("name");
  const Scene s = parse_scene(j.dump(), "test.json");
  CHECK(s.name.empty());
  CHECK(s.part1.name == "part1");
  CHECK(!s.assembled_pose);
  CHECK(s.descriptor.kind == DescriptorKind::skeletal_density);
  CHECK(s.descriptor.sigma == 0.5);
  CHECK(s.frame_budget_ms == 1.0);
  CHECK(s.loop_rate_hz == 1000.0);
  CHECK(s.motion == Motion::six_dof);
  CHECK((s.outputs.energy && s.outputs.force && s.outputs.torque));
  CHECK(s.trajectory.keyframes.empty());
  CHECK(s.grid.padding == 5);

  j["motion"] = "translation";
  j["part2"].erase("pose");
  const Scene t = parse_scene(j.dump(), "test.json");
  CHECK((t.outputs.energy && t.outputs.force && !t.outputs.torque));
  CHECK(t.part2.pose.rotation.coeffs() == Eigen::Quaterniond::Identity().coeffs());
}

TEST_CASE("scene: force and torque imply energy") {
  json j = base_scene();
  j["outputs"] = {"force"};
  const Scene s = parse_scene(j.dump(), "test.json");
  CHECK((s.outputs.energy && s.outputs.force && !s.outputs.torque));
}

TEST_CASE("scene: missing file") {
  try {
    load_scene("/nonexistent/snapfit/scene.json");
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()) == "/nonexistent/snapfit/scene.json: file not found");
  }
}

TEST_CASE("scene: malformed JSON gives line and column") {
  CHECK_ERROR("{\n  \"snapfit_scene\": 1,\n  \"units\": mm\n}", "test.json: invalid JSON at line 3, column 12");
  CHECK_ERROR("{\"snapfit_scene\": 1,", "test.json: invalid JSON at line 1");
  CHECK_ERROR("", "test.json: invalid JSON at line 1");
  CHECK_ERROR("{\"a\": 1} trailing", "invalid JSON at line 1, column 12");
  CHECK_ERROR("{\n\"a\": 1,\n}", "invalid JSON at line 3, column 1: syntax error while parsing object key");
  CHECK_ERROR("\n\n", "invalid JSON at line 3, column 1: syntax error while parsing value - unexpected end of input");
  // Too large for a double: a parse error with its position, not an infinity.
  CHECK_ERROR("{\n\"snapfit_scene\": 1e400}", "test.json: invalid JSON at line 2, column");
  CHECK_ERROR("{\n\"snapfit_scene\": 1e400}", "1e400");
  // Duplicate keys would silently drop one value.
  json j = base_scene();
  std::string text = j.dump();
  text.insert(text.find("\"grid\":{") + 8, "\"padding\":1,");
  CHECK_ERROR(text, "test.json: grid.padding: duplicate field");
}

TEST_CASE("scene: unknown fields name their full path") {
  json j = base_scene();
  j["grid"]["spasing"] = 1;
  CHECK_ERROR(j, "test.json: grid.spasing: unknown field");
  j = base_scene();
  j["colour"] = "red";
  CHECK_ERROR(j, "test.json: colour: unknown field");
  j = base_scene();
  j["part2"]["pose"]["rotation"]["axes"] = {0, 0, 1};
  CHECK_ERROR(j, "test.json: part2.pose.rotation.axes: unknown field");
  j = base_scene();
  j["trajectory"]["keyframes"][1]["velocity"] = {0, 0, 1};
  CHECK_ERROR(j, "test.json: trajectory.keyframes[1].velocity: unknown field");
  j = base_scene();
  j["part1"]["scale"] = 2;  // only mesh parts have a scale
  CHECK_ERROR(j, "test.json: part1.scale: only for mesh parts");
}

TEST_CASE("scene: wrong types name the field") {
  json j = base_scene();
  j["frame"]["budget_ms"] = "1.0";
  CHECK_ERROR(j, "test.json: frame.budget_ms: expected a number, got string");
  j = base_scene();
  j["descriptor"]["sigma"] = "nan";
  CHECK_ERROR(j, "test.json: descriptor.sigma: expected a number, got string");
  j = base_scene();
  j["descriptor"]["lambda_in"] = true;
  CHECK_ERROR(j, "test.json: descriptor.lambda_in: expected a number, got boolean");
  j = base_scene();
  j["assembled_pose"]["position"] = {0, 0};
  CHECK_ERROR(j, "test.json: assembled_pose.position: expected 3 numbers, got 2");
  j = base_scene();
  j["assembled_pose"]["position"] = {0, nullptr, 0};
  CHECK_ERROR(j, "test.json: assembled_pose.position[1]: expected a number, got null");
  j = base_scene();
  j["outputs"] = {"energy", 2};
  CHECK_ERROR(j, "test.json: outputs[1]: expected a string, got number");
  j = base_scene();
  j["part1"]["procedural"]["peg_radius"] = "5";
  CHECK_ERROR(j, "test.json: part1.procedural.peg_radius: expected a number or an array of numbers, got string");
  j = base_scene();
  j["grid"] = 1;
  CHECK_ERROR(j, "test.json: grid: expected an object, got number");
  CHECK_ERROR("[1, 2]", "test.json: expected a JSON object at the top level, got array");
}

TEST_CASE("scene: out-of-range values") {
  struct Case {
    const char* pointer;  // JSON pointer into base_scene()
    json value;
    const char* message;
  };
  const Case cases[] = {
      {"/descriptor/sigma", 0, "descriptor.sigma: must be > 0 (got 0)"},
      {"/descriptor/lambda_in", -3, "descriptor.lambda_in: must be > 0 (got -3)"},
      {"/descriptor/lambda_out", 0, "descriptor.lambda_out: must be > 0"},
      {"/descriptor/tolerance", 1, "descriptor.tolerance: must be in (0, 1) (got 1)"},
      {"/descriptor/tolerance", 0, "descriptor.tolerance: must be in (0, 1)"},
      {"/frame/budget_ms", 0, "frame.budget_ms: must be > 0"},
      {"/frame/rate_hz", -1000, "frame.rate_hz: must be > 0"},
      {"/frame/budget_ms", 2, "frame.budget_ms: must not exceed the loop period"},
      {"/grid/spacing", 0, "grid.spacing: must be > 0"},
      {"/grid/padding", -1, "grid.padding: must be >= 0 (got -1)"},
      {"/haptics/mass_kg", 0, "haptics.mass_kg: must be > 0 (got 0)"},
      {"/haptics/stiffness_n_per_m", -800, "haptics.stiffness_n_per_m: must be > 0"},
      {"/haptics/damping_ratio", -1, "haptics.damping_ratio: must be >= 0"},
      {"/haptics/geometry_gain", -1e-4, "haptics.geometry_gain: must be >= 0"},
      {"/haptics/max_force_n", 0, "haptics.max_force_n: must be > 0"},
      {"/haptics/success_angle_deg", 0, "haptics.success_angle_deg: must be > 0"},
      {"/haptics/settle_s", "1", "haptics.settle_s: expected a number"},
  };
  for (const Case& c : cases) {
    json j = base_scene();
    j[json::json_pointer(c.pointer)] = c.value;
    CHECK_ERROR(j, c.message);
  }
  for (const json& r : {json(7), json(64.5), json(100000)}) {
    json j = base_scene();
    j["grid"] = {{"resolution", r}};
    CHECK_ERROR(j, "test.json: grid.resolution: must be");
  }
  json j = base_scene();
  j["grid"] = {{"resolution", 64.0}};
  CHECK(error_of(j).empty());
  // Checked by the part generator, reported with the field path.
  j = base_scene();
  j["part2"]["procedural"]["radius"] = -1;
  CHECK_ERROR(j, "test.json: part2.procedural.radius: ");
  j = base_scene();
  j["part1"]["procedural"]["type"] = "sphere";
  CHECK_ERROR(j, "test.json: part1.procedural.type");
}

TEST_CASE("scene: structural errors") {
  json j = base_scene();
  j.erase("snapfit_scene");
  CHECK_ERROR(j, "test.json: snapfit_scene: missing");
  j = base_scene();
  j["snapfit_scene"] = 2;
  CHECK_ERROR(j, "test.json: snapfit_scene: unsupported format version 2");
  j = base_scene();
  j["units"] = "furlong";
  CHECK_ERROR(j, "test.json: units: unknown unit 'furlong'");
  j = base_scene();
  j.erase("grid");
  CHECK_ERROR(j, "test.json: grid: missing");
  j = base_scene();
  j["grid"]["resolution"] = 64;
  CHECK_ERROR(j, "test.json: grid: give exactly one of spacing, resolution");
  j = base_scene();
  j["grid"] = {{"padding", 1}};
  CHECK_ERROR(j, "test.json: grid: missing spacing or resolution");
  j = base_scene();
  j["part1"]["mesh"] = "x.stl";
  CHECK_ERROR(j, "test.json: part1: give exactly one of mesh, procedural");
  j = base_scene();
  j["part2"].erase("procedural");
  CHECK_ERROR(j, "test.json: part2: missing mesh or procedural");
  j = base_scene();
  j["part2"].erase("procedural");
  j["part2"]["mesh"] = "no/such/file.stl";
  CHECK_ERROR(j, "test.json: part2.mesh: file not found");
  j["part2"]["mesh"] = ".";  // a directory: said as mesh-info says it
  CHECK_ERROR(j, "test.json: part2.mesh: not a regular file");
  j = base_scene();
  j["descriptor"]["kind"] = "indicator";
  CHECK_ERROR(j, "test.json: descriptor.sigma: only for kind \"skeletal_density\"");
  j = base_scene();
  j["descriptor"]["kind"] = "signed_distance";
  CHECK_ERROR(j, "test.json: descriptor.kind: unknown kind");
  j = base_scene();
  j["motion"] = "rotation";
  CHECK_ERROR(j, "test.json: motion: unknown motion");
  j = base_scene();
  j["outputs"] = json::array();
  CHECK_ERROR(j, "test.json: outputs: must list at least one");
  j = base_scene();
  j["outputs"] = {"energy", "forces"};
  CHECK_ERROR(j, "test.json: outputs[1]: unknown output 'forces'");
  j = base_scene();
  j["outputs"] = {"force", "force"};
  CHECK_ERROR(j, "test.json: outputs[1]: 'force' listed twice");
  j = base_scene();
  j["trajectory"]["keyframes"][1]["time_s"] = 0;
  CHECK_ERROR(j, "test.json: trajectory.keyframes[1].time_s: must be greater than the previous");
  j = base_scene();
  j["trajectory"]["keyframes"][0]["time_s"] = -1;
  CHECK_ERROR(j, "test.json: trajectory.keyframes[0].time_s: must be >= 0");
  j = base_scene();
  j["trajectory"]["keyframes"][1].erase("time_s");
  CHECK_ERROR(j, "test.json: trajectory.keyframes[1].time_s: missing");
  j = base_scene();
  j["trajectory"]["keyframes"] = json::array();
  CHECK_ERROR(j, "test.json: trajectory.keyframes: must hold at least one keyframe");
}

TEST_CASE("scene: rotation errors") {
  json j = base_scene();
  j["assembled_pose"]["rotation"] = {{"quaternion", {1, 0.1, 0, 0}}};
  CHECK_ERROR(j, "test.json: assembled_pose.rotation.quaternion: must be a unit quaternion");
  j["assembled_pose"]["rotation"] = {{"quaternion", {1, 0, 0}}};
  CHECK_ERROR(j, "test.json: assembled_pose.rotation.quaternion: expected 4 numbers, got 3");
  j["assembled_pose"]["rotation"] = {{"axis", {0, 0, 0}}, {"angle_deg", 10}};
  CHECK_ERROR(j, "test.json: assembled_pose.rotation.axis: must be a non-zero vector");
  j["assembled_pose"]["rotation"] = {{"axis", {0, 0, 1}}};
  CHECK_ERROR(j, "test.json: assembled_pose.rotation.angle_deg: missing");
  j["assembled_pose"]["rotation"] = {{"angle_deg", 10}};
  CHECK_ERROR(j, "test.json: assembled_pose.rotation.axis: missing");
  j["assembled_pose"]["rotation"] = {{"axis", {0, 0, 1}}, {"angle_deg", 10}, {"quaternion", {1, 0, 0, 0}}};
  CHECK_ERROR(j, "test.json: assembled_pose.rotation: give either quaternion or axis + angle_deg");
  j["assembled_pose"]["rotation"] = json::object();
  CHECK_ERROR(j, "test.json: assembled_pose.rotation: needs quaternion, or axis and angle_deg");
  // Within 1e-6 of unit norm: accepted and normalised.
  j["assembled_pose"]["rotation"] = {{"quaternion", {1 + 5e-7, 0, 0, 0}}};
  const Scene s = parse_scene(j.dump(), "test.json");
  CHECK(s.assembled_pose->rotation.norm() == doctest::Approx(1.0).epsilon(1e-15));
}

TEST_CASE("scene: translation-only scenes cannot ask for torque or rotate") {
  json j = base_scene();
  j["motion"] = "translation";
  CHECK_ERROR(j, "test.json: outputs: torque needs motion \"6dof\"");
  j["outputs"] = {"energy", "force"};
  // Part 2's orientation is part2.pose's throughout: 3 degrees here, but not when assembled.
  CHECK_ERROR(j, "test.json: assembled_pose.rotation: motion is \"translation\"");
  j["part2"]["pose"].erase("rotation");  // now keyframe 0 is the one that is tilted
  CHECK_ERROR(j, "test.json: trajectory.keyframes[0].rotation: motion is \"translation\"");
  j["trajectory"]["keyframes"][0].erase("rotation");
  CHECK(error_of(j).empty());
}

TEST_CASE("scene: relative mesh paths resolve against the scene file's folder") {
  TempDir dir("relpath");
  write_text(dir.path / "meshes" / "peg.stl", "solid x\nendsolid x\n");
  write_text(dir.path / "scenes" / "sub" / "block.obj", "");
  json j = base_scene();
  j["part2"].erase("procedural");
  j["part2"]["mesh"] = "../meshes/peg.stl";
  j["part1"].erase("procedural");
  j["part1"]["mesh"] = "sub/block.obj";
  const fs::path scene_file = dir.path / "scenes" / "s.json";
  write_text(scene_file, j.dump());
  const Scene s = load_scene(scene_file.string());
  const std::string expect2 = fs::absolute(dir.path / "meshes" / "peg.stl").lexically_normal().string();
  const std::string expect1 = fs::absolute(dir.path / "scenes" / "sub" / "block.obj").lexically_normal().string();
  CHECK(s.part2.mesh_path == expect2);
  CHECK(s.part1.mesh_path == expect1);
  CHECK(fs::path(*s.part2.mesh_path).is_absolute());
  // parse_scene resolves against its origin's folder too; absolute paths stay as they are.
  CHECK(parse_scene(j.dump(), scene_file.string()).part2.mesh_path == expect2);
  j["part2"]["mesh"] = expect2;
  j["part1"]["mesh"] = expect1;
  CHECK(parse_scene(j.dump(), "elsewhere/x.json").part2.mesh_path == expect2);
}

TEST_CASE("scene: mesh unit conversion") {
  TempDir dir("units");
  write_text(dir.path / "peg.stl", "");
  json j = base_scene();
  j["part2"].erase("procedural");
  j["part2"]["mesh"] = (dir.path / "peg.stl").string();
  j["part2"]["mesh_units"] = "m";
  CHECK(parse_scene(j.dump(), "test.json").part2.mesh_scale == doctest::Approx(1000));
  j["part2"]["scale"] = 0.5;
  CHECK(parse_scene(j.dump(), "test.json").part2.mesh_scale == doctest::Approx(500));
  j["part2"]["mesh_units"] = "in";
  CHECK(parse_scene(j.dump(), "test.json").part2.mesh_scale == doctest::Approx(12.7));
  j["part2"].erase("mesh_units");  // defaults to the scene's units
  j["part2"].erase("scale");
  CHECK(parse_scene(j.dump(), "test.json").part2.mesh_scale == 1.0);
  j["units"] = "um";
  j["part2"]["mesh_units"] = "cm";
  CHECK(parse_scene(j.dump(), "test.json").part2.mesh_scale == doctest::Approx(1e4));
  j["part2"]["mesh_units"] = "parsec";
  CHECK_ERROR(j, "test.json: part2.mesh_units: unknown unit 'parsec'");
  j["part2"]["mesh_units"] = "m";
  j["part2"]["scale"] = 0;
  CHECK_ERROR(j, "test.json: part2.scale: must be > 0");
  CHECK(metres_per_unit("km") == 1000.0);
  CHECK_THROWS_AS(metres_per_unit("MM"), Error);
}

TEST_CASE("scene: CAD parts take their units from the file, and their cad fields are checked and round-trip") {
  TempDir dir("cad");
  write_text(dir.path / "parts" / "peg.STEP", "");  // parse_scene only needs the file to exist
  write_text(dir.path / "parts" / "block.igs", "");
  write_text(dir.path / "parts" / "block.stl", "");
  json j = base_scene();
  j["units"] = "cm";
  j["part2"].erase("procedural");
  j["part2"]["mesh"] = "parts/peg.STEP";
  j["part2"]["scale"] = 2;
  j["part2"]["cad"] = json::parse(R"({"solid": "peg [2]", "deflection": 0.05, "angular_deflection_deg": 12.5})");
  j["part1"].erase("procedural");
  j["part1"]["mesh"] = "parts/block.igs";
  const fs::path file = dir.path / "a.json";
  write_text(file, j.dump());
  const Scene a = load_scene(file.string());
  CHECK(a.part2.mesh_scale == 2.0);  // "scale" alone: the reader converts the file's unit
  CHECK(a.part2.cad.solid == std::optional<std::string>("peg [2]"));
  CHECK(a.part2.cad.deflection == std::optional<double>(0.05));
  CHECK(a.part2.cad.angular_deflection_deg == std::optional<double>(12.5));
  CHECK(a.part1.mesh_scale == 1.0);
  CHECK(!a.part1.cad.solid);
  CHECK(!a.part1.cad.deflection);
  const std::string text = scene_to_json(a);
  CHECK(!contains(text, "mesh_units"));
  write_text(dir.path / "b.json", text);
  check_same_scene(a, load_scene((dir.path / "b.json").string()));

  const std::string origin = file.string();
  const auto error_in = [&](const json& scene) {
    try {
      parse_scene(scene.dump(), origin);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  json bad = j;
  bad["part2"]["mesh_units"] = "mm";
  CHECK(contains(error_in(bad), "a.json: part2.mesh_units: STEP and IGES files declare their own length unit"));
  bad = j;
  bad["part2"]["cad"]["deflection"] = -1;
  CHECK(contains(error_in(bad), "a.json: part2.cad.deflection: must be > 0 (got -1)"));
  bad["part2"]["cad"]["deflection"] = "fine";
  CHECK(contains(error_in(bad), "a.json: part2.cad.deflection: expected a number, got string"));
  bad = j;
  bad["part2"]["cad"]["angular_deflection_deg"] = 120;
  CHECK(contains(error_in(bad), "a.json: part2.cad.angular_deflection_deg: must be in (0, 90] (got 120)"));
  bad["part2"]["cad"]["angular_deflection_deg"] = 0;
  CHECK(contains(error_in(bad), "a.json: part2.cad.angular_deflection_deg: must be in (0, 90] (got 0)"));
  bad = j;
  bad["part2"]["cad"]["solid"] = "";
  CHECK(contains(error_in(bad), "a.json: part2.cad.solid: must not be empty"));
  bad["part2"]["cad"]["solid"] = 3;
  CHECK(contains(error_in(bad), "a.json: part2.cad.solid: expected a string, got number"));
  bad = j;
  bad["part2"]["cad"]["deflexion"] = 0.1;
  CHECK(contains(error_in(bad), "a.json: part2.cad.deflexion: unknown field (allowed here: solid, deflection"));
  bad = j;
  bad["part2"]["cad"] = 0.1;
  CHECK(contains(error_in(bad), "a.json: part2.cad: expected an object, got number"));
  bad = j;
  bad["part2"]["mesh"] = "parts/block.stl";
  CHECK(contains(error_in(bad), "a.json: part2.cad: only for STEP and IGES files"));
  bad = base_scene();
  bad["part2"]["cad"] = json::object();
  CHECK(contains(error_in(bad), "a.json: part2.cad: only for mesh parts"));
}

TEST_CASE("scene: quaternion and axis-angle give the same rotation") {
  json j = base_scene();
  j["assembled_pose"]["rotation"] = {{"axis", {1, 2, 2}}, {"angle_deg", 40}};  // axis normalised
  const Eigen::Quaterniond a = parse_scene(j.dump(), "test.json").assembled_pose->rotation;
  const double h = 20.0 * 3.14159265358979323846 / 180.0;
  const double s = std::sin(h) / 3.0;
  j["assembled_pose"]["rotation"] = {{"quaternion", {std::cos(h), 1 * s, 2 * s, 2 * s}}};
  const Eigen::Quaterniond q = parse_scene(j.dump(), "test.json").assembled_pose->rotation;
  CHECK(a.angularDistance(q) < 1e-12);
  const Eigen::Vector3d v(0.3, -1.0, 2.0);
  CHECK((a * v - q * v).norm() < 1e-12);
  // 90 degrees about z maps x to y.
  j["assembled_pose"]["rotation"] = {{"axis", {0, 0, 5}}, {"angle_deg", 90}};
  const Eigen::Quaterniond z90 = parse_scene(j.dump(), "test.json").assembled_pose->rotation;
  CHECK((z90 * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm() < 1e-15);
}
