// Tick positions and labels for slice figures (report/axis_ticks.h).
#include <cmath>
#include <doctest/doctest.h>
#include <vector>

#include "report/axis_ticks.h"

using namespace snapfit;

namespace {

bool near(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i] - b[i]) > 1e-9 * std::max(1.0, std::abs(b[i]))) return false;
  return true;
}

}  // namespace

TEST_CASE("axis ticks: 1-2-5 steps inside the range") {
  // Ticks stay inside [lo, hi]; [0, 9.3] gives 0, 2, 4, 6, 8 (not up to 10).
  AxisTicks t = linear_ticks(0, 9.3, 6);
  CHECK(near(t.major, {0, 2, 4, 6, 8}));
  CHECK(t.step == 2);
  CHECK(near(linear_ticks(0, 9.3, 10).major, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9}));
  CHECK(near(linear_ticks(0, 1, 5).major, {0, 0.5, 1}));
  t = linear_ticks(-0.013, 0.042, 6);
  CHECK(near(t.major, {-0.01, 0, 0.01, 0.02, 0.03, 0.04}));
  CHECK(t.major[1] == 0.0);  // exactly zero, so its label is "0"
  CHECK(near(linear_ticks(1200, 5100, 5).major, {2000, 3000, 4000, 5000}));
  CHECK(near(linear_ticks(3, 3, 5).major, {3}));
  CHECK(linear_ticks(0, HUGE_VAL, 5).major.empty());
  CHECK(linear_ticks(std::nan(""), 1, 5).major.empty());
  // Brute force: every multiple of the step inside the range is a tick, and no more.
  for (double lo : {-17.3, -1.0, 0.0, 0.37}) {
    for (double span : {0.013, 1.0, 7.5, 1234.0}) {
      const AxisTicks a = linear_ticks(lo, lo + span, 7);
      REQUIRE(a.step > 0);
      CHECK(a.major.size() <= 7);
      CHECK(a.major.size() >= 2);
      const double k0 = std::ceil(lo / a.step - 1e-9), k1 = std::floor((lo + span) / a.step + 1e-9);
      CHECK(a.major.size() == std::size_t(k1 - k0 + 1));
    }
  }
}

TEST_CASE("axis ticks: labels carry the places the step needs") {
  CHECK(tick_label(0.1 * 3, 0.1) == "0.3");
  CHECK(tick_label(2, 2) == "2");
  CHECK(tick_label(-0.5, 0.5) == "-0.5");
  CHECK(tick_label(0.75, 0.25) == "0.75");
  CHECK(tick_label(1e-12, 0.1) == "0");
  CHECK(tick_label(2e6, 1e6) == "2e6");
  CHECK(tick_label(1.5e-5, 5e-6) == "1.5e-5");
  CHECK(tick_label(0.001, 0) == "0.001");
  CHECK(tick_label(100000, 0) == "100000");
  CHECK(tick_label(1e-7, 0) == "1e-7");
  CHECK(tick_label(1e9, 0) == "1e9");
}
