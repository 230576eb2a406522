// Thinning a loop's log for display (report/loop_display.h), against brute force.
#include <cmath>
#include <doctest/doctest.h>
#include <random>
#include <vector>

#include "report/loop_display.h"
#include "snapfit/error.h"

using namespace snapfit;

TEST_CASE("loop display: evenly spaced frames keep the ends and stay within the limit") {
  CHECK(evenly_spaced_frames(0, 10).empty());
  CHECK(evenly_spaced_frames(5, 10) == std::vector<std::size_t>{0, 1, 2, 3, 4});
  CHECK(evenly_spaced_frames(11, 3) == std::vector<std::size_t>{0, 5, 10});
  for (std::size_t n : {2u, 3u, 1001u, 60000u, 60001u})
    for (std::size_t limit : {2u, 7u, 1500u}) {
      const std::vector<std::size_t> f = evenly_spaced_frames(n, limit);
      CAPTURE(n);
      CAPTURE(limit);
      REQUIRE(f.size() == std::min(n, limit));
      CHECK(f.front() == 0);
      CHECK(f.back() == n - 1);
      // Strictly increasing, gaps within one of the ideal step.
      const double step = double(n - 1) / double(f.size() - 1);
      for (std::size_t k = 1; k < f.size(); ++k) {
        CHECK(f[k] > f[k - 1]);
        CHECK(std::abs(double(f[k] - f[k - 1]) - step) <= 1.0);
      }
    }
  CHECK_THROWS_AS(evenly_spaced_frames(10, 1), Error);
}

TEST_CASE("loop display: envelopes hold every bucket's extremes in time order") {
  // A minute at 1 kHz: noise, a slow wave and a few one-frame spikes.
  const std::size_t n = 60000;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0, 0.1);
  std::vector<double> time(n), wave(n), spiky(n);
  for (std::size_t i = 0; i < n; ++i) {
    time[i] = 1e-3 * double(i);
    wave[i] = std::sin(time[i]) + noise(rng);
    spiky[i] = 0.4 + 0.01 * noise(rng);
  }
  for (std::size_t i : {17u, 12345u, 59999u}) spiky[i] = 6.0;
  spiky[300] = std::nan("");

  const Envelope e = envelope(time, {wave, spiky}, 4000);
  CHECK(e.bucket == 30);
  REQUIRE(e.time.size() == 4000);
  REQUIRE(e.values.size() == 2);
  for (const auto& v : e.values) CHECK(v.size() == e.time.size());
  for (std::size_t k = 1; k < e.time.size(); ++k) CHECK(e.time[k] >= e.time[k - 1]);
  // Brute force per bucket: the two points are the bucket's minimum and maximum, the one
  // that occurs first first, at the bucket's first and last time.
  for (std::size_t b = 0; b < n / e.bucket; ++b) {
    const std::size_t first = b * e.bucket, last = first + e.bucket - 1;
    CHECK(e.time[2 * b] == time[first]);
    CHECK(e.time[2 * b + 1] == time[last]);
    for (std::size_t s = 0; s < 2; ++s) {
      const std::vector<double>& src = s == 0 ? wave : spiky;
      std::size_t lo = first, hi = first;
      while (!std::isfinite(src[lo])) lo = hi = lo + 1;
      for (std::size_t i = first; i <= last; ++i) {
        if (!std::isfinite(src[i])) continue;
        if (src[i] < src[lo]) lo = i;
        if (src[i] > src[hi]) hi = i;
      }
      const double a = e.values[s][2 * b], c = e.values[s][2 * b + 1];
      CHECK(std::min(a, c) == src[lo]);
      CHECK(std::max(a, c) == src[hi]);
      CHECK((lo <= hi ? a == src[lo] : a == src[hi]));
    }
  }
  // No spike is lost.
  int spikes = 0;
  for (double v : e.values[1]) spikes += v == 6.0;
  CHECK(spikes == 3);

  // Few frames: every frame as it is. A bucket with no finite value gives NaN.
  const Envelope few = envelope({0, 1, 2}, {{1, 2, 3}}, 10);
  CHECK(few.bucket == 1);
  CHECK(few.values[0] == std::vector<double>{1, 2, 3});
  const Envelope gap = envelope({0, 1, 2, 3, 4}, {{std::nan(""), std::nan(""), std::nan(""), 2, 3}}, 4);
  CHECK(gap.bucket == 3);
  CHECK(std::isnan(gap.values[0][0]));
  CHECK(std::isnan(gap.values[0][1]));
  CHECK(gap.values[0][2] == 2);
  CHECK(gap.values[0][3] == 3);
  CHECK(gap.time == std::vector<double>{0, 2, 3, 4});
  CHECK_THROWS_AS(envelope({0, 1}, {{1}}, 10), Error);
  CHECK_THROWS_AS(envelope({0, 1}, {}, 1), Error);
}
