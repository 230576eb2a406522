#include "report/loop_display.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "snapfit/error.h"

namespace snapfit {

std::vector<std::size_t> evenly_spaced_frames(std::size_t frames, std::size_t max_frames) {
  if (max_frames < 2) throw Error("evenly_spaced_frames: max_frames must be at least 2");
  std::vector<std::size_t> out;
  if (frames <= max_frames) {
    for (std::size_t i = 0; i < frames; ++i) out.push_back(i);
    return out;
  }
  // Rounded positions of max_frames points from 0 to frames - 1: strictly increasing,
  // since the step (frames - 1) / (max_frames - 1) is above 1.
  const double step = double(frames - 1) / double(max_frames - 1);
  for (std::size_t k = 0; k < max_frames; ++k) out.push_back(static_cast<std::size_t>(std::llround(k * step)));
  out.back() = frames - 1;
  return out;
}

Envelope envelope(const std::vector<double>& time, const std::vector<std::vector<double>>& series,
                  std::size_t max_points) {
  if (max_points < 2) throw Error("envelope: max_points must be at least 2");
  for (const auto& s : series)
    if (s.size() != time.size())
      throw Error("envelope: a series has " + std::to_string(s.size()) + " values for " + std::to_string(time.size()) +
                  " times");
  Envelope e;
  e.values.resize(series.size());
  const std::size_t n = time.size();
  if (n <= max_points) {
    e.time = time;
    e.values = series;
    return e;
  }
  e.bucket = (n + max_points / 2 - 1) / (max_points / 2);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t first = 0; first < n; first += e.bucket) {
    const std::size_t last = std::min(first + e.bucket, n) - 1;
    e.time.push_back(time[first]);
    if (last > first) e.time.push_back(time[last]);
    for (std::size_t s = 0; s < series.size(); ++s) {
      std::size_t lo = n, hi = n;  // indices of the minimum and maximum
      for (std::size_t i = first; i <= last; ++i) {
        const double v = series[s][i];
        if (!std::isfinite(v)) continue;
        if (lo == n || v < series[s][lo]) lo = i;
        if (hi == n || v > series[s][hi]) hi = i;
      }
      const double vlo = lo == n ? nan : series[s][lo], vhi = hi == n ? nan : series[s][hi];
      if (last == first) {
        e.values[s].push_back(vlo);
      } else if (lo <= hi) {
        e.values[s].push_back(vlo);
        e.values[s].push_back(vhi);
      } else {
        e.values[s].push_back(vhi);
        e.values[s].push_back(vlo);
      }
    }
  }
  return e;
}

}  // namespace snapfit
