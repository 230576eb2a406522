// `snapfit accuracy` (scheduler/tuning/accuracy.h) as a user reads it: every strategy with its
// m', frame time and errors, the choice and why, and the exact product's errors while
// part 2 turns, beside the same final poses at rest.
#include <doctest/doctest.h>
#include <nlohmann/json.hpp>

#include "tests/progress_lines.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("accuracy cli: strategies, the choice, and the background product while turning") {
  const test::CacheDirScope cache;
  const test::TempDir dir;
  const std::string progress = (dir.path / "stderr.txt").string();
  // Its JSON on stdout; stderr (the progress bars) kept apart in a file.
  const test::Command c =
      test::run_command("(" + std::string(SNAPFIT_CLI_PATH) + " accuracy " + SNAPFIT_SOURCE_DIR +
                            "/scenes/default.json --poses 6 --repetitions 60 --turning 0,90 2> " + progress + ")",
                        false);
  INFO(c.output);
  REQUIRE(c.status == 0);
  // Its progress bars (tuning each strategy, the reference) never run past their totals.
  const std::vector<char> raw = test::read_bytes(progress);
  const std::string bars(raw.begin(), raw.end());
  CHECK(bars.find("% (") != std::string::npos);
  CHECK(test::overrun_bars(bars).empty());
  const nlohmann::json j = nlohmann::json::parse(c.output);
  REQUIRE(j["strategies"].size() == 4);
  bool named = false;
  for (const auto& s : j["strategies"]) {
    named |= s["strategy"] == j["lowest_error_within_budget"];
    CHECK(s["modes"].get<std::size_t>() > 0);
  }
  CHECK(named);
  const std::string why = j["why"];  // the rule in words (none may fit on a loaded machine)
  CHECK((why.find("the lowest error of the ") == 0 || why.find("none fits the frame") == 0));
  REQUIRE(j["strategies"][2]["strategy"] == "6dof energy force torque exact-product background");
  REQUIRE(j["strategies"][3]["strategy"] == "6dof energy force torque exact-product background near-far");
  for (int i : {2, 3}) {
    const nlohmann::json& turning = j["strategies"][i]["while_turning"];
    CAPTURE(i);
    REQUIRE(turning.size() == 2);
    CHECK(turning[0]["deg_per_s"] == 0.0);
    CHECK(turning[1]["deg_per_s"] == 90.0);
    // Held still, the background product (and near part) is made for the very pose
    // queried: the same as made for each pose, to float rounding.
    for (const char* q : {"energy_error", "force_error", "torque_error"}) {
      CAPTURE(q);
      CHECK(turning[0][q].get<double>() == doctest::Approx(turning[0]["at_rest"][q].get<double>()).epsilon(1e-3));
      CHECK(turning[1][q].get<double>() >= 0);
    }
  }
}
