// measure_budget_accuracy (include/snapfit/accuracy.h) on a public Assembly: the report
// on the assembly's own device, its strategy saved where it says, and the checks of the
// request.
#include <doctest/doctest.h>
#include <filesystem>

#include "snapfit/accuracy.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "tests/shipped_engine.h"

using namespace snapfit;

TEST_CASE("measure_budget_accuracy: every strategy measured on the assembly's device, the best saved") {
  const test::CacheDirScope cache;
  AssemblyOptions options;
  options.note = [](const std::string&) {};
  const Assembly assembly(test::shipped_scene("peg_hole_translation.json"), options);
  BudgetAccuracyRequest request;
  request.poses = 3;
  request.repetitions = 20;
  request.other_devices = false;
  request.note = [](const std::string&) {};
  const BudgetAccuracy measured = measure_budget_accuracy(assembly, request);
  CHECK(measured.device == assembly.device_name());
  const AccuracyReport& report = measured.report;
  REQUIRE(!report.strategies.empty());
  CHECK(report.poses == 3);
  CHECK(report.best < report.strategies.size());
  CHECK(report.loop == report.best);
  CHECK(!report.why.empty());
  for (const StrategyAccuracy& s : report.strategies) {
    CHECK(s.modes > 0);
    CHECK(s.energy_error >= 0);
  }
  CHECK(std::filesystem::exists(measured.strategy_file));
}

TEST_CASE("measure_budget_accuracy: a bad budget, too few poses or a bad turning speed is refused") {
  AssemblyOptions options;
  options.note = [](const std::string&) {};
  const Assembly assembly(test::shipped_scene("peg_hole_translation.json"), options);
  BudgetAccuracyRequest request;
  request.budget_ms = -1;
  CHECK_THROWS_WITH_AS(measure_budget_accuracy(assembly, request), doctest::Contains("budget"), Error);
  request.budget_ms = 0;  // the scene's
  request.poses = 1;
  CHECK_THROWS_WITH_AS(measure_budget_accuracy(assembly, request), doctest::Contains("poses"), Error);
  request.poses = 2;
  request.turning_deg_per_s = {-5};
  CHECK_THROWS_WITH_AS(measure_budget_accuracy(assembly, request), doctest::Contains("turning"), Error);
}
