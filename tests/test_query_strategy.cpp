// Which query strategy the loop renders (scheduler/tuning/query_strategy.h): the rule (the
// lowest error of the rendered wrench among the strategies that fit), the strategy
// file that keeps the choice, and `snapfit run` choosing, saying why, and reading the
// choice back, checked from its summary.json as a user would.
#include <doctest/doctest.h>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scheduler/tuning/accuracy.h"
#include "scheduler/tuning/engine_tuning.h"
#include "scheduler/tuning/strategy_file.h"
#include "snapfit/assembly.h"
#include "snapfit/tuning.h"
#include "tests/progress_lines.h"
#include "tests/test_support.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

StrategyAccuracy candidate(Interpolation interpolation, bool exact, std::size_t modes, bool fits, double e, double f,
                           double t) {
  StrategyAccuracy s;
  s.variant.force = true;
  s.variant.torque = true;
  s.variant.interpolation = interpolation;
  if (exact) {
    s.variant.rotation = RotationMethod::exact_product;
    s.variant.product_update = ProductUpdate::background;
  }
  s.name = variant_name(s.variant);
  s.modes = modes;
  s.fits = fits;
  s.frame_ms_p50 = 0.3, s.frame_ms_p99 = 0.6;
  s.energy_error = e, s.force_error = f, s.torque_error = t;
  s.estimate_coverage[0] = 0.9, s.estimate_ratio_median[2] = 3.5;
  s.product_ms = exact ? 12.5 : 0;
  return s;
}

AccuracyReport report_of(std::vector<StrategyAccuracy> strategies) {
  AccuracyReport r;
  r.poses = 24;
  r.reference_modes = 2744000;
  r.reference_seconds = 6.1;
  r.strategies = std::move(strategies);
  r.best = r.loop = lowest_error_that_fits(r.strategies);
  r.why = strategy_reason(r.strategies, r.best);
  return r;
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

}  // namespace

TEST_CASE("query strategy: one burst of other work does not rule a strategy out, a slow frame does") {
  AccuracyOptions options;
  options.budget_ms = 1.0;
  options.reserved_ms = 0.2;
  options.repetitions = 200;
  // A timer whose calls return the frame times in `runs` in turn (the last repeats).
  const auto timer_of = [](std::vector<double> runs, int& calls) -> QueryTimer {
    return [runs, &calls](std::size_t, std::size_t count) {
      const double ms = runs[std::min<std::size_t>(calls++, runs.size() - 1)];
      std::vector<double> t(count, 0.3);
      for (std::size_t i = 0; i < count / 20; ++i) t[i] = ms;  // the slowest 5 %: the p99
      return t;
    };
  };
  StrategyAccuracy s = candidate(Interpolation::tricubic, true, 32768, true, 0.01, 0.01, 0.01);
  int calls = 0;
  time_strategy_frame(timer_of({0.7}, calls), options, s);  // within at once: timed once
  CHECK(calls == 1);
  CHECK(s.fits);
  CHECK(s.frame_ms_p99 == doctest::Approx(0.7));

  s.fits = true, calls = 0;
  time_strategy_frame(timer_of({2.6, 0.75}, calls), options, s);  // a burst, then the frame as it is
  CHECK(calls == 2);
  CHECK(s.fits);
  CHECK(s.frame_ms_p99 == doctest::Approx(0.75));
  CHECK(s.frame_ms_p50 == doctest::Approx(0.3));

  s.fits = true, calls = 0;
  time_strategy_frame(timer_of({0.95, 1.4}, calls), options, s);  // slow both times: the lower p99, no fit
  CHECK(calls == 2);
  CHECK_FALSE(s.fits);
  CHECK(s.frame_ms_p99 == doctest::Approx(0.95));

  s.fits = false, calls = 0;  // the tuner said it does not fit: timed once, and it stays so
  time_strategy_frame(timer_of({0.5}, calls), options, s);
  CHECK(calls == 1);
  CHECK_FALSE(s.fits);
}

TEST_CASE("query strategy: the lowest error of the rendered wrench among those that fit") {
  const StrategyAccuracy tricubic = candidate(Interpolation::tricubic, false, 16384, true, 0.09, 0.19, 0.40);
  const StrategyAccuracy trilinear = candidate(Interpolation::trilinear, false, 46336, true, 0.04, 0.15, 10.2);
  const StrategyAccuracy exact = candidate(Interpolation::tricubic, true, 92672, true, 0.03, 0.14, 0.49);
  // The rendered wrench's error is the larger of force and torque: the trilinear sum's
  // small energy error does not make up for its torque.
  CHECK(rendered_error(trilinear) == doctest::Approx(10.2));
  CHECK(rendered_error(exact) == doctest::Approx(0.49));
  CHECK(lowest_error_that_fits({tricubic, trilinear, exact}) == 0);
  // On a device where the product reaches far more modes it wins.
  StrategyAccuracy every_mode = exact;
  every_mode.modes = 2744000, every_mode.force_error = 0.01, every_mode.torque_error = 0.02;
  CHECK(lowest_error_that_fits({tricubic, trilinear, every_mode}) == 2);
  // A more accurate strategy that does not fit the frame is not chosen.
  every_mode.fits = false;
  CHECK(lowest_error_that_fits({tricubic, trilinear, every_mode}) == 0);
  // None fits: the most accurate, said so.
  StrategyAccuracy slow = tricubic;
  slow.fits = false;
  const std::vector<StrategyAccuracy> none_fit = {slow, every_mode};
  CHECK(lowest_error_that_fits(none_fit) == 1);
  CHECK(strategy_reason(none_fit, 1).find("none fits the frame") == 0);
  // The reason, in a few words: the rule, the rendered error and the next best's.
  const std::string why = strategy_reason({tricubic, trilinear, exact}, 0);
  CAPTURE(why);
  CHECK(why == "the lowest error of the 3 that fit the frame (wrench 40 %; next: exact product 49 %)");
  CHECK(strategy_reason({tricubic}, 0) == "the only strategy for this scene (E 9 %, F 19 %, T 40 %)");
  // A translation-only scene has one candidate.
  QueryVariant lines;
  lines.translation_only = true;
  CHECK(accuracy_candidates(lines).size() == 1);
}

TEST_CASE("query strategy: the strategy file keeps the choice, and refuses another key or a tampered one") {
  const test::CacheDirScope cache;
  QueryVariant base;
  base.force = base.torque = true;
  const AccuracyReport saved = report_of({candidate(Interpolation::tricubic, false, 16384, true, 0.09, 0.19, 0.40),
                                          candidate(Interpolation::trilinear, false, 46336, true, 0.04, 0.15, 10.2),
                                          candidate(Interpolation::tricubic, true, 92672, true, 0.03, 0.14, 0.29)});
  REQUIRE(saved.best == 2);
  save_strategy("key A", saved);
  const auto loaded = load_strategy("key A", base);
  REQUIRE(loaded);
  CHECK(loaded->best == 2);
  CHECK(loaded->why == saved.why);
  REQUIRE(loaded->strategies.size() == 3);
  for (std::size_t i = 0; i < 3; ++i) {
    const StrategyAccuracy &a = loaded->strategies[i], &b = saved.strategies[i];
    CHECK(a.name == b.name);
    CHECK(variant_name(a.variant) == variant_name(b.variant));
    CHECK(a.modes == b.modes);
    CHECK(a.torque_error == b.torque_error);
    CHECK(a.product_ms == b.product_ms);
    CHECK(a.estimate_ratio_median[2] == b.estimate_ratio_median[2]);
  }
  std::string heard;
  CHECK_FALSE(load_strategy("key B", base, [&](const std::string& m) { heard = m; }));
  // A payload whose recorded choice does not follow the rule is not trusted.
  const std::string text = accuracy_report_to_json(saved);
  nlohmann::json tampered = nlohmann::json::parse(text);
  tampered["best"] = 0;
  CHECK_THROWS_WITH_AS(accuracy_report_from_json(tampered.dump(), base), doctest::Contains("does not follow the rule"),
                       Error);
  CHECK_THROWS_AS(accuracy_report_from_json("{\"poses\": 3}", base), Error);
}

TEST_CASE(
    "query strategy: snapfit run starts safe, measures the strategies after the loop, then renders the most accurate "
    "that fits") {
  const test::CacheDirScope cache;
  const test::TempDir out;
  const std::string scene = std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json";
  const std::string run = std::string(SNAPFIT_CLI_PATH) + " run " + scene + " --simulated-time --out ";
  const test::Command first = test::run_command(run + (out.path / "first").string());
  INFO(first.output);
  REQUIRE(first.status == 0);
  CHECK(test::overrun_bars(first.output).empty());  // tuning, descriptors, strategies: none past its total
  // Every kernel the main job built (both PoCL drivers, all four strategies) compiled silently.
  CHECK(first.output.find("with compiler messages") == std::string::npos);
  CHECK(first.output.find("warning") == std::string::npos);
  // The first run measures m' (and keeps it, unless the machine is too busy for any m').
  const bool measured = first.output.find("measured and saved to") != std::string::npos ||
                        first.output.find("measured, not saved: no m' fits the budget") != std::string::npos;
  CHECK(measured);
  // Nothing measured yet: the loop starts on the tricubic sum and does not wait for the
  // strategies, which are measured after it.
  CHECK(first.output.find("the loop starts on 6dof energy force torque tricubic") < first.output.find("[7/7]"));
  CHECK(first.output.find("measuring the strategies' errors for the next run") > first.output.find("[7/7]"));
  const nlohmann::json s1 = read_json(out.path / "first" / "summary.json")["query_strategy"];
  CHECK(s1["chosen_by"] == "safe start (the strategies are measured after the loop)");
  CHECK(s1["name"] == "6dof energy force torque tricubic");
  REQUIRE(s1["candidates"].size() == 4);  // tricubic, trilinear, exact product, its near-far split
  // The rule, checked from the JSON alone.
  std::size_t best = 0;
  const auto error = [&](const nlohmann::json& c) {
    return std::max(c["force_error"].get<double>(), c["torque_error"].get<double>());
  };
  const auto& c = s1["candidates"];
  for (std::size_t i = 1; i < c.size(); ++i) {
    const bool fits = c[i]["fits_budget"], best_fits = c[best]["fits_budget"];
    if ((fits && !best_fits) || (fits == best_fits && error(c[i]) < error(c[best]))) best = i;
  }
  const std::string why = s1["why"];
  CHECK(why.find("a safe start; ") == 0);
  CHECK(why.find("the next run renders " + c[best]["strategy"].get<std::string>()) != std::string::npos);
  const nlohmann::json loop1 = read_json(out.path / "first" / "summary.json")["haptic_loop"];
  CHECK(loop1["assembled"] == true);

  // The second run reads the choice back and renders the most accurate that fits.
  const test::Command second = test::run_command(run + (out.path / "second").string());
  INFO(second.output);
  REQUIRE(second.status == 0);
  CHECK(second.output.find("measuring the strategies' errors") == std::string::npos);
  const nlohmann::json s2 = read_json(out.path / "second" / "summary.json")["query_strategy"];
  CHECK(s2["chosen_by"] == "lowest error that fits (strategy file)");
  CHECK(s2["name"] == c[best]["strategy"]);
  // The rule in words: on a loaded machine none may fit, and the reason says so.
  const std::string why2 = s2["why"];
  CHECK((why2.find("the lowest error of the ") == 0 || why2.find("none fits the frame") == 0));
  CHECK(s2["strategy_file"] == s1["strategy_file"]);

  // The library's way in chooses by the same rule on the assembly's device.
  const Assembly assembly(load_scene(scene));
  const QueryVariant api = most_accurate_strategy(assembly);
  const std::string api_name = variant_name(api);
  CAPTURE(api_name);
  bool among = false;
  for (const auto& candidate : s1["candidates"]) among |= candidate["strategy"] == api_name;
  CHECK(among);
  auto engine = assembly.make_query_engine(api);
  CHECK(variant_name(engine->variant()) == api_name);
}

TEST_CASE("query strategy: --strategy names one, a translation-only scene has only its lines") {
  const test::TempDir out;
  const std::string cli = std::string(SNAPFIT_CLI_PATH);
  const test::Command named =
      test::run_command(cli + " run " + SNAPFIT_SOURCE_DIR + "/scenes/default.json --strategy trilinear --modes 2048 " +
                        "--simulated-time --out " + (out.path / "named").string());
  INFO(named.output);
  REQUIRE(named.status == 0);
  const nlohmann::json s = read_json(out.path / "named" / "summary.json")["query_strategy"];
  CHECK(s["name"] == "6dof energy force torque trilinear");
  CHECK(s["chosen_by"] == "JobRequest::strategy");
  CHECK(s["candidates"].is_null());

  const test::Command refused = test::run_command(cli + " run " + SNAPFIT_SOURCE_DIR +
                                                  "/scenes/peg_hole_translation.json --strategy exact-product " +
                                                  "--modes 2048 --simulated-time --out " + (out.path / "t").string());
  CHECK(refused.status != 0);
  CHECK(refused.output.find("translation-only scene has one strategy") != std::string::npos);

  // The near-far split sums grid samples: a part whose spectrum comes from balls is named.
  Scene balls = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  balls.descriptor.kind = DescriptorKind::indicator;
  balls.part2.descriptor.source = SpectrumSource::spheres;
  const std::string balls_file = (out.path / "balls.json").string();
  std::ofstream(balls_file) << scene_to_json(balls);
  const test::Command no_near = test::run_command(cli + " run " + balls_file + " --strategy near-far --modes 2048 " +
                                                  "--simulated-time --out " + (out.path / "b").string());
  CHECK(no_near.status != 0);
  CHECK(no_near.output.find("part 2's descriptor.source is \"spheres\"") != std::string::npos);
}
