#include "scheduler/tuning/device_choice.h"

#include <algorithm>
#include <limits>

#include "snapfit/error.h"

namespace snapfit {
namespace {

const TimingPoint* at_modes(const TuningResult& t, std::size_t modes) {
  for (const TimingPoint& p : t.points)
    if (p.modes == modes) return &p;
  return nullptr;
}

}  // namespace

std::size_t lowest_latency(const std::vector<TuningResult>& tunings) {
  if (tunings.empty()) throw Error("device choice: no tuned devices to choose from");
  // The largest m' level that every candidate measured.
  std::size_t common = 0;
  for (const TimingPoint& p : tunings.front().points) {
    bool everywhere = true;
    for (const TuningResult& t : tunings) everywhere = everywhere && at_modes(t, p.modes);
    if (everywhere) common = std::max(common, p.modes);
  }
  std::size_t best = 0;
  double best_ms = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < tunings.size(); ++i) {
    const TuningResult& t = tunings[i];
    // Lower is better: fitting first, then the p99 at the common level (or -m').
    const double ms = common ? at_modes(t, common)->p99_ms : -double(t.chosen_modes);
    const bool better = (t.fits && !tunings[best].fits) || (t.fits == tunings[best].fits && ms < best_ms);
    if (i == 0 || better) best = i, best_ms = ms;
  }
  return best;
}

std::size_t loop_device(const std::vector<TuningResult>& tunings, const std::vector<bool>& in_caller_thread) {
  if (tunings.empty()) throw Error("device choice: no tuned devices to choose from");
  if (in_caller_thread.size() != tunings.size())
    throw Error("device choice: one caller-thread flag per tuning expected");
  bool any_fits = false;
  std::size_t largest = 0;
  for (const TuningResult& t : tunings) any_fits = any_fits || t.fits;
  for (const TuningResult& t : tunings)
    if (t.fits || !any_fits) largest = std::max(largest, t.chosen_modes);
  std::vector<std::size_t> candidates;
  for (std::size_t i = 0; i < tunings.size(); ++i)
    if ((tunings[i].fits || !any_fits) && 2 * tunings[i].chosen_modes >= largest) candidates.push_back(i);
  std::vector<std::size_t> in_caller;
  for (const std::size_t i : candidates)
    if (in_caller_thread[i]) in_caller.push_back(i);
  const std::vector<std::size_t>& pool = in_caller.empty() ? candidates : in_caller;
  std::vector<TuningResult> subset;
  for (const std::size_t i : pool) subset.push_back(tunings[i]);
  return pool[lowest_latency(subset)];
}

}  // namespace snapfit
