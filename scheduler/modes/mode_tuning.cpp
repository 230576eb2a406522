#include "scheduler/modes/mode_tuning.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>

#include "core/quantile.h"
#include "snapfit/error.h"

namespace snapfit {

CostModel fit_cost_model(const std::vector<TimingPoint>& points) {
  CostModel model;
  if (points.empty()) return model;
  if (points.size() == 1) {
    model.per_mode_ms = points[0].p99_ms / std::max<double>(1, points[0].modes);
    return model;
  }
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const TimingPoint& p : points) {
    sx += p.modes;
    sy += p.p99_ms;
    sxx += double(p.modes) * p.modes;
    sxy += double(p.modes) * p.p99_ms;
  }
  const double n = points.size(), den = n * sxx - sx * sx;
  model.per_mode_ms = den > 0 ? (n * sxy - sx * sy) / den : 0;
  model.fixed_ms = (sy - model.per_mode_ms * sx) / n;
  return model;
}

std::vector<std::size_t> mode_ladder(std::size_t min_modes, std::size_t max_modes, double factor) {
  if (max_modes == 0) throw Error("m' ladder: the engine has no modes");
  if (!(factor > 1)) throw Error("m' ladder: the factor between levels must be > 1");
  std::vector<std::size_t> ladder;
  double m = std::max<std::size_t>(1, std::min(min_modes, max_modes));
  while (m < max_modes) {
    const std::size_t level = std::max<std::size_t>(64, static_cast<std::size_t>(std::llround(m / 64.0)) * 64);
    if (level >= max_modes) break;
    if (ladder.empty() || level > ladder.back()) ladder.push_back(level);
    m *= factor;
  }
  ladder.push_back(max_modes);
  return ladder;
}

TuningResult pick_modes(std::vector<TimingPoint> points, double budget_ms, double margin) {
  if (points.empty()) throw Error("auto-tuning: no timings to choose from");
  if (!(budget_ms > 0) || !(margin >= 0 && margin < 1))
    throw Error("auto-tuning: budget must be > 0 and margin in [0, 1)");
  std::sort(points.begin(), points.end(), [](const TimingPoint& a, const TimingPoint& b) { return a.modes < b.modes; });
  TuningResult r;
  r.points = points;
  r.budget_ms = budget_ms;
  r.margin = margin;
  r.model = fit_cost_model(points);
  const double target = r.target_ms();
  r.chosen_modes = points.front().modes;
  for (const TimingPoint& p : points)
    if (p.p99_ms <= target && r.model.predict_ms(p.modes) <= target) {
      r.chosen_modes = p.modes;
      r.fits = true;
    }
  const std::time_t now = std::time(nullptr);
  char date[32];
  std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  r.created = date;
  return r;
}

namespace {

TimingPoint time_level(const QueryTimer& timer, std::size_t modes, const TuneOptions& options) {
  timer(modes, options.warmup);
  std::vector<double> times = timer(modes, options.repetitions);
  TimingPoint p;
  p.modes = modes;
  p.samples = times.size();
  p.p50_ms = quantile(times, 0.5);
  p.p99_ms = quantile(times, 0.99);
  p.max_ms = times.empty() ? 0 : *std::max_element(times.begin(), times.end());
  return p;
}

}  // namespace

TuningResult tune_modes(const QueryTimer& timer, std::size_t max_modes, const TuneOptions& options) {
  const std::vector<std::size_t> ladder = mode_ladder(options.min_modes, max_modes, options.ladder_factor);
  const double target = options.budget_ms * (1.0 - options.margin);
  std::vector<TimingPoint> points;
  // Each level once, plus a second time for each level that misses the target.
  const std::uint64_t per_level = options.warmup + options.repetitions;
  std::uint64_t total = ladder.size() * per_level, done = 0;
  if (options.progress) options.progress(0, total);
  for (std::size_t modes : ladder) {
    TimingPoint p = time_level(timer, modes, options);
    done += per_level;
    if (p.p99_ms > target) {
      // A burst of other work on the machine inflates one measurement; a level that is
      // really too slow is slow again. Keep the lower p99 of two.
      total += per_level;
      if (options.progress) options.progress(done, total);
      const TimingPoint again = time_level(timer, modes, options);
      done += per_level;
      if (again.p99_ms < p.p99_ms) p = again;
    }
    if (options.progress) options.progress(done, total);
    points.push_back(p);
    if (p.p99_ms > options.stop_factor * target) break;  // larger m' only gets slower
  }
  if (options.progress) options.progress(total, total);
  return pick_modes(std::move(points), options.budget_ms, options.margin);
}

std::vector<std::size_t> loop_levels(const TuningResult& tuning) {
  std::vector<std::size_t> levels;
  for (const TimingPoint& p : tuning.points)
    if (p.modes <= tuning.chosen_modes) levels.push_back(p.modes);
  if (levels.empty()) levels.push_back(tuning.chosen_modes);
  return levels;
}

}  // namespace snapfit
