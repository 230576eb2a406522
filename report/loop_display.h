#pragma once
// Thinning a haptic loop's log for display (report.html): a long run has a frame a
// millisecond, far more than a page can draw. loop.csv keeps every frame.
#include <cstddef>
#include <vector>

namespace snapfit {

// At most `max_frames` (>= 2) frame indices out of `frames`, evenly spaced, the first and
// the last always among them; every frame when there are few enough.
std::vector<std::size_t> evenly_spaced_frames(std::size_t frames, std::size_t max_frames);

// Series over time drawn as envelopes: with more than `max_points` frames, the frames go
// into buckets of `bucket` consecutive frames and each bucket becomes two points, at its
// first and its last frame's time, holding each series' minimum and maximum over the
// bucket in the order they occur. Spikes (a missed frame, a contact) are never lost, and
// every point is at most one bucket away from its frame's time.
struct Envelope {
  std::size_t bucket = 1;                   // frames a bucket (1: every frame as it is)
  std::vector<double> time;                 // increasing
  std::vector<std::vector<double>> values;  // one vector a series, aligned with `time`
};

// `series` are aligned with `time` (non-finite values are left out of a bucket's extremes;
// a bucket with none gives NaN). max_points >= 2.
Envelope envelope(const std::vector<double>& time, const std::vector<std::vector<double>>& series,
                  std::size_t max_points);

}  // namespace snapfit
