// The snapfit tool's options as a newcomer meets them (cli/main.cpp, cli/parse_options.h):
// --version answers, --help gives defaults, a number that must be positive says so, and
// an output folder that cannot be written is refused before any work.
#include <doctest/doctest.h>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "tests/test_support.h"

using namespace snapfit;

namespace {

test::Command cli(const std::string& args) { return test::run_command(std::string(SNAPFIT_CLI_PATH) + " " + args); }

const std::string kScene = std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json";

}  // namespace

TEST_CASE("cli options: --version prints the version") {
  const test::Command c = cli("--version");
  INFO(c.output);
  CHECK(c.status == 0);
  CHECK(c.output.rfind("snapfit 0.", 0) == 0);
}

TEST_CASE("cli options: --help gives each option's default") {
  const test::Command query = cli("query --help");
  INFO(query.output);
  CHECK(query.output.find("--modes UINT=32768") != std::string::npos);
  CHECK(query.output.find("--interpolation TEXT=tricubic") != std::string::npos);
  const test::Command fields = cli("fields --help"), spheres = cli("spheres --help");
  INFO(fields.output);
  INFO(spheres.output);
  CHECK(fields.output.find("--part TEXT=2") != std::string::npos);  // the two commands' parts differ
  CHECK(spheres.output.find("--part TEXT=1") != std::string::npos);
}

TEST_CASE("cli options: a number that must be positive says so") {
  const test::Command c = cli("search " + kScene + " --step-deg 0");
  INFO(c.output);
  CHECK(c.status != 0);
  CHECK(c.output.find("--step-deg: must be > 0, got 0") != std::string::npos);
  CHECK(c.output.size() < 200);  // not CLI11's range up to the largest double
}

TEST_CASE("cli options: an output folder that cannot be written is refused before any work") {
  for (const std::string& command : {"run " + kScene + " --simulated-time --modes 512", "search " + kScene}) {
    const test::Command c = cli(command + " --out /proc/snapfit-cannot-write");
    INFO(c.output);
    CHECK(c.status != 0);
    CHECK(c.output.find("--out /proc/snapfit-cannot-write: cannot make the folder") != std::string::npos);
    CHECK(c.output.find("[2/7]") == std::string::npos);  // the parts were not built
  }
}

TEST_CASE("cli options: every field of query's JSON is documented, and the batch's time says it is the batch's") {
  const test::CacheDirScope cache;
  const test::Command c = test::run_command(std::string(SNAPFIT_CLI_PATH) + " query " +
                                                std::string(SNAPFIT_SOURCE_DIR) + "/scenes/collision_only.json" +
                                                " --collision --modes 512 --pose 0,0,5 --pose 3,0,-10",
                                            false);
  INFO(c.output);
  REQUIRE(c.status == 0);
  std::ifstream doc_file(std::string(SNAPFIT_SOURCE_DIR) + "/docs/cli.md");
  const std::string doc((std::istreambuf_iterator<char>(doc_file)), std::istreambuf_iterator<char>());
  std::istringstream lines(c.output);
  std::vector<nlohmann::json> rows;
  for (std::string line; std::getline(lines, line);) rows.push_back(nlohmann::json::parse(line));
  REQUIRE(rows.size() == 2);
  for (const auto& row : rows)
    for (const auto& [key, value] : row.items()) {
      CAPTURE(key);
      CHECK(doc.find("`" + key + "`") != std::string::npos);
    }
  CHECK(rows[0]["batch_poses"] == 2);
  CHECK(rows[0]["batch_mean_ms"] == rows[1]["batch_mean_ms"]);
  CHECK(rows[0].count("time_ms") == 0);
}
