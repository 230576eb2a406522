// Auto-tuning of m' (scheduler/modes/mode_tuning.h) from injected timings with a known cost,
// and the tuning file (scheduler/modes/tuning_file.h): round trip, key changes, corruption.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <filesystem>

#include "scheduler/modes/mode_tuning.h"
#include "scheduler/modes/tuning_file.h"
#include "scheduler/tuning/device_choice.h"
#include "scheduler/tuning/engine_tuning.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

// A device whose query takes exactly fixed + per_mode * m' ms, except every
// `spike_every`-th query, which takes `spike_ms`.
QueryTimer linear_timer(double fixed, double per_mode, std::size_t spike_every = 0, double spike_ms = 0) {
  return [=, n = std::size_t(0)](std::size_t modes, std::size_t count) mutable {
    std::vector<double> t;
    for (std::size_t i = 0; i < count; ++i, ++n)
      t.push_back(spike_every && n % spike_every == spike_every - 1 ? spike_ms : fixed + per_mode * modes);
    return t;
  };
}

TuningKey sample_key() {
  TuningKey k;
  k.platform = "Portable Computing Language OpenCL 3.0 PoCL 3.1";
  k.device = "cpu-test";
  k.driver = "3.1";
  k.variant = "6dof energy force torque tricubic";
  k.scene_features = "fft 64x64x64 torque_spectra 1 spacing 0.6";
  return k;
}

}  // namespace

TEST_CASE("auto-tune: the m' ladder grows geometrically in multiples of 64 and ends at the maximum") {
  const auto ladder = mode_ladder(512, 100000, std::sqrt(2.0));
  REQUIRE(ladder.size() >= 8);
  CHECK(ladder.front() == 512);
  CHECK(ladder.back() == 100000);
  for (std::size_t i = 1; i < ladder.size(); ++i) {
    CHECK(ladder[i] > ladder[i - 1]);
    if (i + 1 < ladder.size()) CHECK(ladder[i] % 64 == 0);
  }
  CHECK(mode_ladder(512, 300, 2.0) == std::vector<std::size_t>{300});
  CHECK_THROWS_AS(mode_ladder(512, 0, 2.0), Error);
}

TEST_CASE("auto-tune: the least-squares cost model recovers a linear cost exactly") {
  std::vector<TimingPoint> pts;
  for (std::size_t m : {512, 1024, 4096, 16384}) pts.push_back({m, 0, 0.04 + 3e-5 * m, 0, 100});
  const CostModel model = fit_cost_model(pts);
  CHECK(model.fixed_ms == doctest::Approx(0.04).epsilon(1e-9));
  CHECK(model.per_mode_ms == doctest::Approx(3e-5).epsilon(1e-9));
}

TEST_CASE("auto-tune: picks the largest m' whose p99 fits the budget with margin") {
  TuneOptions opt;
  opt.budget_ms = 1.0;
  opt.margin = 0.25;
  opt.repetitions = 200;
  opt.warmup = 5;
  const double fixed = 0.05, per_mode = 2e-5;  // fits up to (0.75 - 0.05) / 2e-5 = 35,000 modes
  const TuningResult r = tune_modes(linear_timer(fixed, per_mode), 1 << 20, opt);
  // The expected pick, worked out from the ladder independently of pick_modes.
  std::size_t expected = 0;
  for (std::size_t m : mode_ladder(opt.min_modes, 1 << 20, opt.ladder_factor))
    if (fixed + per_mode * m <= 0.75) expected = m;
  CHECK(r.chosen_modes == expected);
  CHECK(r.chosen_modes <= 35000);
  CHECK(r.fits);
  CHECK(r.target_ms() == doctest::Approx(0.75));
  // The sweep stopped once a level cost more than 1.5x the target.
  CHECK(r.points.back().p99_ms > 1.5 * 0.75);
  CHECK(r.points.back().modes < (1u << 20));
  CHECK(r.model.per_mode_ms == doctest::Approx(per_mode).epsilon(1e-6));
  // The loop's ladder ends at the chosen m'.
  const auto levels = loop_levels(r);
  CHECK(levels.back() == r.chosen_modes);
  CHECK(std::is_sorted(levels.begin(), levels.end()));
}

TEST_CASE("auto-tune: p99, not the mean: 2% slow queries push the pick down") {
  TuneOptions opt;
  opt.repetitions = 500;
  opt.warmup = 0;
  // Every 50th query takes 0.9 ms: the mean barely moves, the p99 is 0.9 ms > 0.75.
  const TuningResult r = tune_modes(linear_timer(0.05, 2e-5, 50, 0.9), 1 << 20, opt);
  CHECK_FALSE(r.fits);
  CHECK(r.chosen_modes == r.points.front().modes);
  // 1 slow query in 500 (0.2%) is within the 1% the p99 ignores.
  const TuningResult ok = tune_modes(linear_timer(0.05, 2e-5, 500, 0.9), 1 << 20, opt);
  CHECK(ok.fits);
  CHECK(ok.chosen_modes > 16384);
}

TEST_CASE("auto-tune: a burst of other work during one level's timing neither ends the sweep nor lowers the pick") {
  TuneOptions opt;
  opt.repetitions = 200;
  opt.warmup = 5;
  const TuningResult quiet = tune_modes(linear_timer(0.05, 2e-5), 1 << 20, opt);
  REQUIRE(quiet.fits);
  // The first timed run of the level below the pick is slowed 3x throughout (every query,
  // as when another process takes the core); timed again, it is as quiet as the rest.
  const std::size_t burst_level = quiet.points[quiet.points.size() - 4].modes;
  const QueryTimer quiet_timer = linear_timer(0.05, 2e-5);
  int timed_runs_of_burst_level = 0;
  const QueryTimer bursty = [&](std::size_t modes, std::size_t count) {
    std::vector<double> t = quiet_timer(modes, count);
    if (modes == burst_level && count == opt.repetitions && timed_runs_of_burst_level++ == 0)
      for (double& x : t) x *= 3.0;
    return t;
  };
  const TuningResult r = tune_modes(bursty, 1 << 20, opt);
  CHECK(timed_runs_of_burst_level == 2);
  CHECK(r.chosen_modes == quiet.chosen_modes);
  CHECK(r.points.size() == quiet.points.size());
  // A level that is slow every time it is timed still ends the sweep and is not picked.
  const QueryTimer slow_level = [&](std::size_t modes, std::size_t count) {
    std::vector<double> t = quiet_timer(modes, count);
    if (modes == burst_level)
      for (double& x : t) x *= 3.0;
    return t;
  };
  const TuningResult slow = tune_modes(slow_level, 1 << 20, opt);
  CHECK(slow.points.back().modes == burst_level);
  CHECK(slow.chosen_modes < burst_level);
}

TEST_CASE("auto-tune: a budget that no level meets picks the smallest level and says so") {
  TuneOptions opt;
  opt.repetitions = 50;
  const TuningResult r = tune_modes(linear_timer(2.0, 1e-5), 1 << 16, opt);
  CHECK_FALSE(r.fits);
  CHECK(r.chosen_modes == opt.min_modes);
  CHECK_THROWS_AS(pick_modes({}, 1.0, 0.25), Error);
  CHECK_THROWS_AS(pick_modes({{512, 0.1, 0.1, 0.1, 10}}, 1.0, 1.5), Error);
}

TEST_CASE("tuning file: round trip, reuse, and re-tune on a key change") {
  test::CacheDirScope scope;
  TuneOptions opt;
  opt.repetitions = 50;
  const TuningResult r = tune_modes(linear_timer(0.05, 2e-5), 1 << 18, opt);
  const TuningKey key = sample_key();
  CHECK_FALSE(load_tuning(key).has_value());
  save_tuning(key, r);
  CHECK(fs::exists(tuning_file_path(key)));
  CHECK(fs::path(tuning_file_path(key)).parent_path() == scope.folder("tuning"));
  const auto back = load_tuning(key);
  REQUIRE(back.has_value());
  CHECK(back->chosen_modes == r.chosen_modes);
  CHECK(back->fits == r.fits);
  CHECK(back->created == r.created);
  REQUIRE(back->points.size() == r.points.size());
  for (std::size_t i = 0; i < r.points.size(); ++i) {
    CHECK(back->points[i].modes == r.points[i].modes);
    CHECK(back->points[i].p99_ms == r.points[i].p99_ms);
  }
  CHECK(back->model.per_mode_ms == r.model.per_mode_ms);

  // Any field of the key names another file (or, on a hash collision, a stale one).
  for (int field = 0; field < 8; ++field) {
    TuningKey other = key;
    switch (field) {
      case 0:
        other.platform += "x";
        break;
      case 1:
        other.device += "x";
        break;
      case 2:
        other.driver = "3.2";
        break;
      case 3:
        other.variant = "6dof energy force torque trilinear";
        break;
      case 4:
        other.scene_features = "fft 96x64x64 torque_spectra 1 spacing 0.6";
        break;
      case 5:
        other.budget_ms = 0.5;
        break;
      case 6:
        other.margin = 0.1;
        break;
      case 7:
        other.pace_hz = 1000;
        break;
    }
    CAPTURE(field);
    CHECK(other.text() != key.text());
    CHECK_FALSE(load_tuning(other).has_value());
  }
}

TEST_CASE("tuning file: a corrupt, truncated or foreign file is reported and ignored, never trusted") {
  test::CacheDirScope scope;
  const TuningKey key = sample_key();
  TuneOptions opt;
  opt.repetitions = 20;
  save_tuning(key, tune_modes(linear_timer(0.05, 2e-5), 1 << 16, opt));
  const std::string path = tuning_file_path(key);
  const std::vector<char> good = test::read_bytes(path);

  std::vector<std::string> notes;
  const auto note = [&](const std::string& m) { notes.push_back(m); };
  std::vector<char> flipped = good;
  flipped[flipped.size() - 5] ^= 0x20;
  test::write_bytes(path, flipped);
  CHECK_FALSE(load_tuning(key, note).has_value());
  test::write_bytes(path, std::vector<char>(good.begin(), good.begin() + good.size() / 2));
  CHECK_FALSE(load_tuning(key, note).has_value());
  test::write_text(path, "not a cache file at all");
  CHECK_FALSE(load_tuning(key, note).has_value());
  REQUIRE(notes.size() == 3);
  for (const std::string& n : notes) {
    CHECK(n.find(path) != std::string::npos);
    CHECK(n.find("re-tuning") != std::string::npos);
  }
  // Saving again repairs it.
  save_tuning(key, tune_modes(linear_timer(0.05, 2e-5), 1 << 16, opt));
  CHECK(load_tuning(key).has_value());
  // Malformed JSON in a well-formed container is an error naming the problem.
  CHECK_THROWS_WITH_AS(tuning_from_json("{\"points\": []}"), doctest::Contains("malformed"), Error);
}

TEST_CASE("tuning file: a tuning in which nothing fits is not kept, one that fits is kept and read back") {
  test::CacheDirScope scope;
  const TuningKey key = sample_key();
  TuneOptions opt;
  opt.repetitions = 20;
  std::vector<std::string> notes;
  const auto note = [&](const std::string& n) { notes.push_back(n); };
  // A machine busy elsewhere: 0.9 ms before any mode, above the 0.75 ms the margin leaves.
  const EngineTuning busy = tune_and_keep(key, linear_timer(0.9, 1e-5), 1 << 16, opt, false, note);
  CHECK(!busy.result.fits);
  CHECK(!busy.from_file);
  CHECK(!load_tuning(key).has_value());
  REQUIRE(!notes.empty());
  CHECK(notes.back().find("tuning not saved: not even m'") != std::string::npos);
  // The next run measures again, on a quiet machine, and keeps what fits.
  const EngineTuning quiet = tune_and_keep(key, linear_timer(0.05, 2e-5), 1 << 16, opt, false, note);
  REQUIRE(quiet.result.fits);
  CHECK(!quiet.from_file);
  const EngineTuning again = tune_and_keep(key, linear_timer(0.9, 1e-5), 1 << 16, opt, false, note);
  CHECK(again.from_file);
  CHECK(again.result.chosen_modes == quiet.result.chosen_modes);
}

TEST_CASE("tuning file: an unwritable cache folder is a clear error, not a crash") {
  test::CacheDirScope scope;
  test::write_text(scope.folder("tuning").string(), "a file where the tuning folder should be");
  TuneOptions opt;
  opt.repetitions = 10;
  const TuningResult r = tune_modes(linear_timer(0.05, 2e-5), 1 << 14, opt);
  CHECK_THROWS_AS(save_tuning(sample_key(), r), Error);
  CHECK(fs::is_regular_file(scope.folder("tuning")));
}

TEST_CASE("device choice: the loop goes to the device with the lowest tuned latency") {
  TuneOptions opt;
  opt.repetitions = 50;
  const TuningResult cpu = tune_modes(linear_timer(0.05, 2e-5), 1 << 18, opt);
  const TuningResult gpu = tune_modes(linear_timer(0.03, 1e-6), 1 << 18, opt);
  const TuningResult slow = tune_modes(linear_timer(0.9, 1e-5), 1 << 18, opt);
  CHECK(lowest_latency({cpu, gpu}) == 1);
  CHECK(lowest_latency({gpu, cpu}) == 0);
  CHECK(lowest_latency({slow, cpu, gpu}) == 2);
  CHECK(lowest_latency({slow, cpu}) == 1);  // fitting beats not fitting
  CHECK(lowest_latency({cpu}) == 0);
  CHECK_THROWS_AS(lowest_latency({}), Error);
}

TEST_CASE("device choice: the loop prefers a device that runs kernels in its own thread when its m' is close") {
  TuneOptions opt;
  opt.repetitions = 50;
  // pthread-like: low fixed cost; basic-like (caller thread): higher per-mode cost.
  const TuningResult pthread = tune_modes(linear_timer(0.05, 2e-5), 1 << 18, opt);
  const TuningResult basic = tune_modes(linear_timer(0.05, 3e-5), 1 << 18, opt);
  const TuningResult far_slower = tune_modes(linear_timer(0.05, 9e-5), 1 << 18, opt);
  const TuningResult misfit = tune_modes(linear_timer(0.9, 1e-5), 1 << 18, opt);
  REQUIRE(pthread.fits);
  REQUIRE(basic.fits);
  REQUIRE(2 * basic.chosen_modes >= pthread.chosen_modes);
  REQUIRE(2 * far_slower.chosen_modes < pthread.chosen_modes);
  REQUIRE(!misfit.fits);
  CHECK(lowest_latency({pthread, basic}) == 0);  // by latency alone, pthread
  CHECK(loop_device({pthread, basic}, {false, true}) == 1);
  CHECK(loop_device({basic, pthread}, {true, false}) == 0);
  // Less than half the m': latency decides.
  CHECK(loop_device({pthread, far_slower}, {false, true}) == 0);
  // Fitting beats not fitting, caller thread or not.
  CHECK(loop_device({misfit, pthread}, {true, false}) == 1);
  // No caller-thread device: lowest latency.
  CHECK(loop_device({basic, pthread}, {false, false}) == 1);
  CHECK_THROWS_AS(loop_device({}, {}), Error);
  CHECK_THROWS_AS(loop_device({pthread}, {true, false}), Error);
}
