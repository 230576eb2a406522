// The scene format's one description (io/scene_fields.h) against what the reader
// accepts, what the writer writes and what docs/scenes.md lists: from outside, through
// parse_scene and scene_to_json and the text of the docs.
#include <cmath>
#include <doctest/doctest.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>

#include "io/scene_fields.h"
#include "snapfit/error.h"
#include "snapfit/scene.h"
#include "tests/test_support.h"

using nlohmann::json;
using namespace snapfit;
namespace sf = snapfit::scene_schema;

namespace {

// A small valid scene that leaves every optional section out.
json bare_scene() {
  return json::parse(R"({
    "snapfit_scene": 1,
    "units": "mm",
    "part1": {"procedural": {"type": "hole_block", "peg_radius": 5, "hole_depth": 20, "width": 30, "height": 30}},
    "part2": {"procedural": {"type": "peg", "radius": 5, "length": 30}},
    "grid": {"spacing": 0.6, "padding": 5}
  })");
}

// The scene with part 2 from a STEP file in `dir` (parse_scene only needs it to exist).
json with_step_part2(json j, const test::TempDir& dir) {
  std::ofstream(dir.file("peg.step")) << "";
  j["part2"].erase("procedural");
  j["part2"]["mesh"] = dir.file("peg.step");
  return j;
}

std::string refusal_of(const json& j) {
  try {
    parse_scene(j.dump(), "schema.json");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// The names of one section in scene_fields(), in order.
std::vector<std::string> documented_names(const std::string& section) {
  std::vector<std::string> names;
  for (const SceneFieldInfo& f : scene_fields())
    if (f.section == section) names.push_back(f.name);
  return names;
}

// Where each section sits in a scene (JSON pointer), for a scene that has it.
const std::pair<const char*, const char*> kSectionAt[] = {
    {"top", ""},
    {"part", "/part2"},
    {"part.descriptor", "/part2/descriptor"},
    {"cad", "/part2/cad"},
    {"pose", "/part2/pose"},
    {"rotation", "/part2/pose/rotation"},
    {"descriptor", "/descriptor"},
    {"grid", "/grid"},
    {"frame", "/frame"},
    {"trajectory", "/trajectory"},
    {"keyframe", "/trajectory/keyframes/0"},
    {"haptics", "/haptics"},
    {"vps", "/vps"},
    {"vps.hybrid", "/vps/hybrid"},
};

std::string read_scene_docs() {
  std::ifstream in(std::string(SNAPFIT_SOURCE_DIR) + "/docs/scenes.md");
  REQUIRE(in);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A value of field `f` that is allowed and differs from its default.
template <typename T>
json value_for(const sf::Field<T>& f) {
  const T defaults{};
  return std::visit(
      [&](auto&& m) -> json {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, std::monostate>) {
          return nullptr;
        } else if constexpr (std::is_same_v<M, sf::Choice<T>>) {
          // The names, "a, b or c"; the first that is not the default.
          std::string names = m.names();
          for (const char* sep : {", ", " or "})
            for (std::size_t at; (at = names.find(sep)) != std::string::npos;)
              names.replace(at, std::string(sep).size(), "|");
          std::istringstream in(names);
          for (std::string name; std::getline(in, name, '|');)
            if (name != m.get(defaults)) return name;
          FAIL("no name other than the default for " << f.name);
          return nullptr;
        } else {
          using V = std::decay_t<decltype(defaults.*m)>;
          if constexpr (std::is_same_v<V, bool>) {
            return !(defaults.*m);
          } else if constexpr (std::is_same_v<V, std::string> || std::is_same_v<V, std::optional<std::string>>) {
            return "value of " + f.name;
          } else {
            std::optional<double> def;
            if constexpr (std::is_same_v<V, double> || std::is_same_v<V, int>) def = double(defaults.*m);
            const sf::NumberRange& r = f.range;
            std::vector<double> candidates;
            if (def) candidates = {*def * 0.97, *def - 1, *def + 1};
            if (std::isfinite(r.low) && std::isfinite(r.high)) candidates.push_back(r.low + 0.37 * (r.high - r.low));
            if (std::isfinite(r.low)) candidates.push_back(r.low + 1.25);
            candidates.push_back(1.25);
            for (double c : candidates) {
              if (r.integer) c = std::round(c);
              if (r.holds(c) && (!def || c != *def)) return c;
            }
            FAIL("no allowed value other than the default for " << f.name);
            return nullptr;
          }
        }
      },
      f.value);
}

// For each plain field of `table` (the section at `at` in `base`): a scene with that
// field set to a value other than its default reads, writes it, and reads back the same.
template <typename T>
void check_plain_fields(const json& base, const std::string& at, const std::vector<sf::Field<T>>& table) {
  for (const sf::Field<T>& f : table) {
    const json value = value_for(f);
    if (value.is_null()) continue;  // read by hand
    CAPTURE(at);
    CAPTURE(f.name);
    CAPTURE(value.dump());
    json j = base;
    if (at == "/grid" && f.name == "resolution") j["grid"].erase("spacing");  // exactly one of them
    j[json::json_pointer(at + "/" + f.name)] = value;
    std::string text;
    try {
      text = scene_to_json(parse_scene(j.dump(), "schema.json"));
    } catch (const Error& e) {
      FAIL("refused: " << e.what());
    }
    const json written = json::parse(text);
    const json::json_pointer where(at + "/" + f.name);
    REQUIRE(written.contains(where));
    if (value.is_number())
      CHECK(double(written[where]) == double(value));
    else
      CHECK(written[where] == value);
    CHECK(scene_to_json(parse_scene(text, "schema.json")) == text);
  }
}

}  // namespace

TEST_CASE("scene schema: docs/scenes.md's field tables are those the one description prints") {
  const std::string docs = read_scene_docs();
  const std::string open = "<!-- scene fields: ", close = "<!-- end scene fields -->\n";
  std::set<std::string> blocks;
  for (std::size_t at = docs.find(open); at != std::string::npos; at = docs.find(open, at + 1)) {
    const std::size_t name_end = docs.find(" -->\n", at);
    REQUIRE(name_end != std::string::npos);
    const std::string section = docs.substr(at + open.size(), name_end - at - open.size());
    CAPTURE(section);
    CHECK(blocks.insert(section).second);
    const std::size_t begin = name_end + 5, end = docs.find(close, begin);
    REQUIRE(end != std::string::npos);
    std::string expected;
    try {
      expected = scene_fields_markdown(section);
    } catch (const Error& e) {
      FAIL("docs/scenes.md has a block for an unknown section: " << e.what());
    }
    // On failure: `snapfit scene-check --fields` prints every block as it should read.
    CHECK(docs.substr(begin, end - begin) == expected);
  }
  for (const std::string& section : scene_field_sections()) {
    CAPTURE(section);
    CHECK(blocks.count(section) == 1);
  }
  // No table of fields in the "Fields" chapter outside the printed blocks.
  const std::size_t chapter = docs.find("\n## Fields\n"), next = docs.find("\n## ", chapter + 1);
  REQUIRE(chapter != std::string::npos);
  bool inside = false;
  std::istringstream lines(docs.substr(chapter, next - chapter));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind(open, 0) == 0) inside = true;
    if (line + "\n" == close) inside = false;
    if (line.rfind("| `", 0) == 0) {
      CAPTURE(line);
      CHECK(inside);
    }
  }
}

TEST_CASE("scene schema: each section's reader accepts exactly the fields the docs list") {
  const test::TempDir dir;
  json base = with_step_part2(bare_scene(), dir);
  base["part2"]["pose"] = {{"rotation", {{"axis", {0, 0, 1}}, {"angle_deg", 10}}}};
  base["trajectory"] = {{"keyframes", {{{"time_s", 0}}}}};
  std::set<std::string> seen;
  for (const auto& [section, at] : kSectionAt) {
    CAPTURE(section);
    json j = base;
    j[json::json_pointer(std::string(at) + "/no_such_field")] = 1;
    const std::string error = refusal_of(j);
    const std::string lead = "no_such_field: unknown field (allowed here: ";
    const std::size_t from = error.find(lead);
    REQUIRE_MESSAGE(from != std::string::npos, error);
    const std::string allowed = error.substr(from + lead.size(), error.rfind(')') - from - lead.size());
    std::string listed;
    for (const std::string& name : documented_names(section)) listed += (listed.empty() ? "" : ", ") + name;
    CHECK(allowed == listed);
    seen.insert(section);
  }
  for (const std::string& section : scene_field_sections()) {
    CAPTURE(section);
    CHECK(seen.count(section) == 1);
  }
}

TEST_CASE("scene schema: every plain field reads, writes and reads back a value other than its default") {
  const test::TempDir dir;
  const json base = bare_scene();
  check_plain_fields(base, "", sf::top_fields());
  check_plain_fields(base, "/part2", sf::part_fields());
  json spheres = base;
  spheres["descriptor"] = {{"kind", "indicator"}};
  spheres["part2"]["descriptor"] = {{"source", "spheres"}};
  check_plain_fields(spheres, "/part2/descriptor", sf::part_descriptor_fields());
  check_plain_fields(with_step_part2(base, dir), "/part2/cad", sf::cad_fields());
  check_plain_fields(base, "/descriptor", sf::descriptor_fields());
  check_plain_fields(base, "/grid", sf::grid_fields());
  check_plain_fields(base, "/frame", sf::frame_fields());
  check_plain_fields(base, "/haptics", sf::haptics_fields());
  check_plain_fields(base, "/vps", sf::vps_fields());
  check_plain_fields(base, "/vps/hybrid", sf::vps_hybrid_fields());
}

TEST_CASE("scene schema: scenes with every field read by hand round-trip, and the writer writes every field") {
  const test::TempDir dir;
  std::ofstream(dir.file("block.stl")) << "";
  // A: part 1 procedural, part 2 from STEP with its cad and spheres fields, every
  // optional field set; B: part 1 from a mesh file in other units.
  json a = with_step_part2(bare_scene(), dir);
  a["name"] = "every field";
  a["part2"]["cad"] = {{"solid", "peg"}, {"deflection", 0.02}, {"angular_deflection_deg", 15}};
  a["part2"]["descriptor"] = {{"source", "spheres"}, {"tolerance", 0.4}};
  a["descriptor"] = {{"kind", "indicator"}};
  a["part2"]["pose"] = {{"position", {1, 2, 3}}, {"rotation", {{"axis", {0, 1, 0}}, {"angle_deg", 3}}}};
  a["assembled_pose"] = {{"position", {0, 0, -20}}};
  a["grid"]["region"] = {{"min", {-1, -1, -25}}, {"max", {1, 1, 12}}};
  a["grid"]["region_margin"] = 2;
  a["frame"] = {{"budget_ms", 0.9}};
  a["outputs"] = {"energy", "force"};
  a["trajectory"] = {{"keyframes",
                      {{{"time_s", 0}, {"position", {1, 2, 3}}, {"rotation", {{"quaternion", {1, 0, 0, 0}}}}},
                       {{"time_s", 1.5}, {"position", {0, 0, -20}}}}}};
  a["haptics"] = {{"mass_kg", 0.1},
                  {"rot_stiffness_nm_per_rad", 0.2},
                  {"geometry_gain", 0.3},
                  {"success_position", 0.4},
                  {"contact_spacing", 0.5}};
  a["vps"] = {{"voxel_size", 0.25},
              {"braking_n_s_per_m", 0.1},
              {"hybrid",
               {{"region", "pair"}, {"radius_tolerance", 0.1}, {"offset_tolerance", 0.2}, {"angle_tolerance_deg", 5}}}};
  json b = bare_scene();
  b["part1"].erase("procedural");
  b["part1"]["mesh"] = dir.file("block.stl");
  b["part1"]["mesh_units"] = "cm";
  b["part1"]["scale"] = 2;

  std::set<std::pair<std::string, std::string>> written;  // (section, field)
  for (const json& j : {a, b}) {
    const Scene scene = parse_scene(j.dump(), dir.file("scene.json"));
    const std::string text = scene_to_json(scene);
    CHECK(scene_to_json(parse_scene(text, dir.file("scene.json"))) == text);
    const json out = json::parse(text);
    for (const auto& [section, at] : kSectionAt) {
      std::vector<std::string> places = {at};
      if (std::string(section) == "part") places = {"/part1", "/part2"};
      for (const std::string& place : places) {
        const json::json_pointer p(place);
        if (!out.contains(p)) continue;
        for (const auto& item : out[p].items()) written.insert({section, item.key()});
      }
    }
  }
  // What a written scene never holds: the rotation as axis and angle (the writer gives
  // the quaternion, exactly), and the resolution beside the spacing (one of the two).
  const std::set<std::pair<std::string, std::string>> read_only = {
      {"rotation", "axis"}, {"rotation", "angle_deg"}, {"grid", "resolution"}};
  for (const SceneFieldInfo& f : scene_fields()) {
    CAPTURE(f.section);
    CAPTURE(f.name);
    CHECK(written.count({f.section, f.name}) + read_only.count({f.section, f.name}) == 1);
  }
  for (const auto& [section, name] : written) {
    CAPTURE(section);
    CAPTURE(name);
    const std::vector<std::string> names = documented_names(section);
    CHECK(std::find(names.begin(), names.end(), name) != names.end());
  }
}

TEST_CASE("scene schema: ranges say what they allow, and a section's table is printed or refused by name") {
  CHECK(sf::above(0).text() == "> 0");
  CHECK(sf::at_least(0).text() == ">= 0");
  CHECK(sf::within(0, 1, "(]").text() == "in (0, 1]");
  CHECK(sf::whole_numbers(0, 16).text() == "an integer in [0, 16]");
  CHECK(sf::any_number().text().empty());
  CHECK(!sf::within(0, 1, "(]").holds(0));
  CHECK(sf::within(0, 1, "(]").holds(1));
  CHECK(!sf::whole_numbers(0, 16).holds(1.5));
  CHECK(scene_fields_markdown("haptics").find("| `mass_kg` | number | `0.05` | > 0; ") != std::string::npos);
  CHECK_THROWS_WITH_AS(scene_fields_markdown("haptic"), doctest::Contains("unknown section 'haptic'"), Error);
}

TEST_CASE("scene schema: docs/scenes.md's procedural parts list exactly the parameters each generator accepts") {
  const std::string docs = read_scene_docs();
  const std::size_t chapter = docs.find("\n## Procedural parts\n"), next = docs.find("\n## ", chapter + 1);
  REQUIRE(chapter != std::string::npos);
  // Each "### `type`" (or "### `a` and `b`") heading with the parameters its table lists.
  std::vector<std::pair<std::vector<std::string>, std::set<std::string>>> types;
  std::istringstream lines(docs.substr(chapter, next - chapter));
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("### ", 0) == 0) {
      types.emplace_back();
      for (std::size_t at = line.find('`'); at != std::string::npos; at = line.find('`', line.find('`', at + 1) + 1))
        types.back().first.push_back(line.substr(at + 1, line.find('`', at + 1) - at - 1));
    } else if (line.rfind("| `", 0) == 0 && !types.empty()) {
      types.back().second.insert(line.substr(3, line.find('`', 3) - 3));
    }
  }
  REQUIRE(types.size() == 3);
  for (const auto& [names, documented] : types)
    for (const std::string& type : names) {
      CAPTURE(type);
      json j = bare_scene();
      j["part2"]["procedural"] = {{"type", type}, {"no_such_parameter", 1}};
      const std::string error = refusal_of(j);
      const std::string lead = "known parameters: ";
      const std::size_t from = error.find(lead);
      REQUIRE_MESSAGE(from != std::string::npos, error);
      std::set<std::string> known;
      std::istringstream list(error.substr(from + lead.size()));
      for (std::string name; std::getline(list, name, ',');) {
        while (!name.empty() && name.front() == ' ') name.erase(0, 1);
        known.insert(name);
      }
      CHECK(known == documented);
    }
}
