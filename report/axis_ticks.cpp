#include "report/axis_ticks.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace snapfit {

AxisTicks linear_ticks(double lo, double hi, int max_ticks) {
  AxisTicks t;
  if (!std::isfinite(lo) || !std::isfinite(hi) || !std::isfinite(hi - lo)) return t;
  if (!(hi > lo)) {
    t.major.push_back(lo);
    return t;
  }
  max_ticks = std::max(max_ticks, 2);
  const double base = std::pow(10.0, std::floor(std::log10((hi - lo) / max_ticks)));
  double step = base;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    step = m * base;
    const double n = std::floor(hi / step + 1e-9) - std::ceil(lo / step - 1e-9) + 1;
    if (n <= max_ticks) break;
  }
  t.step = step;
  const double k0 = std::ceil(lo / step - 1e-9), k1 = std::floor(hi / step + 1e-9);
  for (double k = k0; k <= k1 && t.major.size() < 1000; ++k) t.major.push_back(k == 0 ? 0.0 : k * step);
  return t;
}

std::string tick_label(double value, double step) {
  char buf[64];
  if (!std::isfinite(value)) {
    std::snprintf(buf, sizeof buf, "%g", value);
    return buf;
  }
  step = std::abs(step);
  if (!(step > 0) || !std::isfinite(step)) step = std::abs(value);
  if (std::abs(value) < step * 1e-9 || value == 0) return "0";
  const int e = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  const double mag = std::abs(value);
  if (mag < 1e6 && step >= 1e-4) {
    int decimals = std::max(0, -e);
    // Steps like 0.25 need a place more than their exponent says.
    while (decimals < 12) {
      const double scaled = step * std::pow(10.0, decimals);
      if (std::abs(scaled - std::round(scaled)) <= 1e-6 * scaled) break;
      ++decimals;
    }
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
    return buf;
  }
  // Exponent form with as many mantissa places as the step needs: "1.5e-5", "2e6".
  const int places = std::clamp(static_cast<int>(std::floor(std::log10(mag) + 1e-9)) - e, 0, 12);
  std::snprintf(buf, sizeof buf, "%.*e", places, value);
  std::string text = buf;
  const std::size_t at = text.find('e');
  std::string mantissa = text.substr(0, at), exponent = text.substr(at + 1);
  const bool negative = exponent[0] == '-';
  exponent = exponent.substr(1);
  exponent.erase(0, std::min(exponent.find_first_not_of('0'), exponent.size() - 1));
  return mantissa + "e" + (negative ? "-" : "") + exponent;
}

}  // namespace snapfit
