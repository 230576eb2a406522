// `snapfit spheres` end to end on a shipped scene (JSON lines, the ParaView export, bad
// input) and the VTK PolyData writer (io/vtp_export.h).
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "io/vtp_export.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

}  // namespace

TEST_CASE("spheres command: one JSON line per tolerance and a VTP piece per tolerance") {
  const test::TempDir dir;
  const std::string vtp = dir.file("peg.vtp");
  const test::Command c =
      test::run_command(std::string(SNAPFIT_CLI_PATH) + " spheres " + SNAPFIT_SOURCE_DIR +
                            "/scenes/default.json --part 2 --tolerance 2 1.5 --json --samples 20000 --vtp " + vtp,
                        false);
  REQUIRE(c.status == 0);
  std::istringstream lines(c.output);
  std::string line;
  std::vector<nlohmann::json> rows;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] == '{') rows.push_back(nlohmann::json::parse(line));
  REQUIRE(rows.size() == 2);
  CHECK(rows[0]["tolerance"].get<double>() == 2.0);
  CHECK(rows[1]["tolerance"].get<double>() == 1.5);
  for (const auto& r : rows) {
    CHECK(r["part"].get<int>() == 2);
    CHECK(r["balls"].get<int>() > 0);
    CHECK(r["balls"].get<int>() <= r["sampled_balls"].get<int>());
    CHECK(r["volume_error"].get<double>() >= r["volume_error_ci95"][0].get<double>());
    CHECK(r["volume_error"].get<double>() <= r["volume_error_ci95"][1].get<double>());
    CHECK(r["hausdorff_sampled"].get<double>() <= r["hausdorff_bound"].get<double>() * (1 + 1e-4));
    CHECK(r["seconds"].get<double>() > 0);
    // The peg: radius 5, length 30 (scenes/default.json).
    CHECK(r["solid_volume"].get<double>() == doctest::Approx(3.14159265 * 25 * 30).epsilon(0.01));
  }
  const std::vector<char> bytes = test::read_bytes(vtp);
  const std::string text(bytes.begin(), bytes.end());
  CHECK(count_of(text, "<Piece ") == 2);
  CHECK(text.find("NumberOfPoints=\"" + std::to_string(rows[0]["balls"].get<int>()) + "\"") != std::string::npos);
  CHECK(text.find("Name=\"radius\"") != std::string::npos);
}

TEST_CASE("spheres command: bad input names the option") {
  const std::string cli = std::string(SNAPFIT_CLI_PATH) + " spheres " + SNAPFIT_SOURCE_DIR + "/scenes/default.json";
  const test::Command part = test::run_command(cli + " --part 3");
  CHECK(part.status == 1);
  CHECK(part.output.find("--part: expected 1 or 2") != std::string::npos);
  const test::Command tolerance = test::run_command(cli + " --tolerance 0");
  CHECK(tolerance.status == 1);
  CHECK(tolerance.output.find("tolerance must be a positive number") != std::string::npos);
  const test::Command order = test::run_command(cli + " --order size");
  CHECK(order.status == 1);
  CHECK(order.output.find("--order: expected sdf or distance") != std::string::npos);
}

TEST_CASE("vtp export: pieces, scalars and errors") {
  const test::TempDir dir;
  const std::string path = dir.file("p.vtp");
  write_points_vtp(path, {{{{1, 2, 3}, {4, 5, 6}}, {{"radius", {0.5, 0.25}}}}, {{{7, 8, 9}}, {{"radius", {1}}}}});
  const std::vector<char> bytes = test::read_bytes(path);
  const std::string text(bytes.begin(), bytes.end());
  CHECK(count_of(text, "<Piece ") == 2);
  CHECK(text.find("NumberOfPoints=\"2\"") != std::string::npos);
  CHECK(text.find("0.5 0.25") != std::string::npos);
  CHECK(text.find("1 2 3 4 5 6") != std::string::npos);
  CHECK(text.find("0 1 \n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n1 2 ") !=
        std::string::npos);
  CHECK(test::error_of([&] { write_points_vtp(path, {}); }).find("no point sets") != std::string::npos);
  CHECK(test::error_of([&] {
          write_points_vtp(path, {{{{1, 2, 3}}, {{"radius", {}}}}});
        }).find("has 0 values for 1 points") != std::string::npos);
  CHECK(test::error_of([&] {
          write_points_vtp(path, {{{{std::nan(""), 2, 3}}, {}}});
        }).find("non-finite") != std::string::npos);
}
