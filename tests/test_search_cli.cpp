// `snapfit search` end to end on a shipped scene (the peg and the 0.5 mm clearance
// hole, at twice the scene's grid spacing so the maps stay small): the assembled pose,
// or one the peg's symmetry makes equal, comes out first; the files and bad input.
#include <cctype>
#include <doctest/doctest.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "engine/maps/map_fft.h"
#include "pipeline/prepare_parts.h"
#include "snapfit/scene.h"
#include "snapfit/search.h"
#include "test_support.h"

using namespace snapfit;

namespace {

Pose pose_of(const nlohmann::json& j) {
  Pose p;
  p.translation = Eigen::Vector3d(j["position"][0], j["position"][1], j["position"][2]);
  const nlohmann::json& q = j["rotation"]["quaternion"];
  p.rotation = Eigen::Quaterniond(double(q[0]), double(q[1]), double(q[2]), double(q[3]));
  return p;
}

// The peg is a cylinder, the same turned about its axis and end over end: a pose is
// equivalent to the assembled one when it puts the axis' two end points where the
// assembled pose puts them (in either order). The larger of the two distances.
double axis_mismatch(const Pose& pose, const Pose& assembled, const Mesh& peg) {
  Eigen::Vector3d lo = peg.vertices.front(), hi = lo;
  for (const Eigen::Vector3d& v : peg.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Eigen::Vector3d c = 0.5 * (lo + hi), a = c - Eigen::Vector3d(0, 0, 0.5 * (hi.z() - lo.z())),
                        b = c + Eigen::Vector3d(0, 0, 0.5 * (hi.z() - lo.z()));
  const double same =
      std::max((pose.apply(a) - assembled.apply(a)).norm(), (pose.apply(b) - assembled.apply(b)).norm());
  const double flip =
      std::max((pose.apply(a) - assembled.apply(b)).norm(), (pose.apply(b) - assembled.apply(a)).norm());
  return std::min(same, flip);
}

}  // namespace

TEST_CASE("snapfit search: on the shipped peg and hole the assembled pose comes out first") {
  test::CacheDirScope cache;
  test::TempDir dir;
  std::ifstream in(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/peg_hole_clearance_0p5.json");
  std::stringstream text;
  text << in.rdbuf();
  std::string scene_text = text.str();
  const std::size_t at = scene_text.find("\"spacing\": 0.6");
  REQUIRE(at != std::string::npos);
  scene_text.replace(at, 14, "\"spacing\": 1.2");
  const std::string scene_file = dir.file("scene.json");
  test::write_text(scene_file, scene_text);
  const Scene scene = load_scene(scene_file);
  REQUIRE(scene.assembled_pose.has_value());
  const Mesh peg = prepare_parts(scene).part2.mesh;

  const test::Command run =
      test::run_command(std::string(SNAPFIT_CLI_PATH) + " search " + scene_file +
                            " --rotations 48 --top 3 --refine-queries 80 --out " + dir.file("out"),
                        false);
  INFO(run.output);
  REQUIRE(run.status == 0);
  CHECK(run.output.find("covering radius") != std::string::npos);
  std::vector<nlohmann::json> poses;
  std::istringstream lines(run.output);
  for (std::string line; std::getline(lines, line);)
    if (!line.empty() && line[0] == '{') poses.push_back(nlohmann::json::parse(line));
  REQUIRE(poses.size() == 3);
  for (std::size_t k = 0; k < poses.size(); ++k) {
    CHECK(poses[k]["rank"] == k + 1);
    CHECK(poses[k].contains("energy"));
    CHECK(poses[k]["refined"].contains("energy"));
    if (k > 0) CHECK(double(poses[k]["energy"]) >= double(poses[k - 1]["energy"]));
  }
  const double h = 1.2;
  const double found = axis_mismatch(pose_of(poses[0]), *scene.assembled_pose, peg);
  const double refined = axis_mismatch(pose_of(poses[0]["refined"]), *scene.assembled_pose, peg);
  REQUIRE(poses[0]["refined"].contains("energy_minimum"));
  const double energy_minimum =
      axis_mismatch(pose_of(poses[0]["refined"]["energy_minimum"]), *scene.assembled_pose, peg);
  MESSAGE("first pose: axis ends " << found << " mm from the assembled pose's, the energy's minimum " << energy_minimum
                                   << " mm, refined on the rendered potential " << refined << " mm");
  CHECK(found <= h);  // the grid holds the aligned rotation; the map's translation step is h
  // The rendered potential (energy x gain + rigid contact) rests at the fit, within the
  // contact's skin: 0.35 of its distance spacing h / 3, 0.14 mm here.
  CHECK(refined <= 0.35 * h / 3 + 0.01);
  CHECK(poses[0]["refined"]["by"] == "rendered potential (energy x gain + rigid contact)");
  for (const char* file : {"best_per_rotation.csv", "search.html", "top.jsonl"})
    CHECK(std::filesystem::exists(dir.file("out") + "/" + file));
  std::ifstream csv(dir.file("out") + "/best_per_rotation.csv");
  std::size_t rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  const std::size_t grid_at = run.output.find("SO(3) grid: ");
  REQUIRE(grid_at != std::string::npos);
  CHECK(rows == 1 + std::stoul(run.output.substr(grid_at + 12)));

  // Every inverse FFT built finds the same top pose (a grid point, so exactly), its
  // energy equal to single-precision rounding; the output names the FFT used.
  CHECK(run.output.find("map FFT: ") != std::string::npos);
  for (const MapFft kind : map_ffts_built()) {
    const test::Command forced =
        test::run_command(std::string(SNAPFIT_CLI_PATH) + " search " + scene_file +
                              " --rotations 48 --top 1 --refine-queries 1 --map-fft " + map_fft_name(kind),
                          false);
    INFO(forced.output);
    REQUIRE(forced.status == 0);
    CHECK(forced.output.find("map FFT: " + map_fft_name(kind) + " (--map-fft)") != std::string::npos);
    nlohmann::json top;
    std::istringstream forced_lines(forced.output);
    for (std::string line; std::getline(forced_lines, line);)
      if (!line.empty() && line[0] == '{') top = nlohmann::json::parse(line);
    REQUIRE(top.contains("energy"));
    CHECK(top["map_fft"] == map_fft_name(kind));
    CHECK(top["position"] == poses[0]["position"]);
    CHECK(top["rotation"] == poses[0]["rotation"]);
    CHECK(std::abs(double(top["energy"]) - double(poses[0]["energy"])) <= 1e-5 * std::abs(double(poses[0]["energy"])));
  }

  const test::Command both =
      test::run_command(std::string(SNAPFIT_CLI_PATH) + " search " + scene_file + " --rotations 10 --step-deg 20");
  CHECK(both.status != 0);
  CHECK(both.output.find("give one of them") != std::string::npos);
  const test::Command missing = test::run_command(std::string(SNAPFIT_CLI_PATH) + " search " + dir.file("none.json"));
  CHECK(missing.status != 0);
  CHECK(missing.output.find("none.json") != std::string::npos);
}

TEST_CASE("snapfit search --help names the map FFTs this build has, and each is one the search takes") {
  const std::vector<std::string> built = map_ffts_in_this_build();
  REQUIRE(!built.empty());
  CHECK(built.front() == "clfft");  // always built
  std::string listed = "auto (the fastest, measured once per device and size)";
  for (const std::string& name : built) {
    CHECK(map_fft_name(parse_map_fft(name)) == name);
    listed += ", " + name;
  }
  const auto help = test::run_command(std::string(SNAPFIT_CLI_PATH) + " search --help");
  CHECK(help.status == 0);
  // CLI11 wraps long help lines: compare with the whitespace folded.
  const auto folded = [](const std::string& text) {
    std::string out;
    for (char c : text) {
      const bool space = std::isspace(static_cast<unsigned char>(c));
      if (!space)
        out += c;
      else if (!out.empty() && out.back() != ' ')
        out += ' ';
    }
    return out;
  };
  CHECK(folded(help.output).find(folded(listed + " (those this build has)")) != std::string::npos);
}
