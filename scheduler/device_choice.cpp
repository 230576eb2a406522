#include "scheduler/device_choice.h"

#include <limits>

#include "engine/error.h"

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
    const bool better = (t.fits && !tunings[best].fits) ||
                        (t.fits == tunings[best].fits && ms < best_ms);
    if (i == 0 || better) best = i, best_ms = ms;
  }
  return best;
}

}  // namespace snapfit
