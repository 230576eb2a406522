#pragma once
// IEEE 754 binary16 from float, for spectra stored as half floats on the device.
#include <cmath>
#include <cstdint>
#include <cstring>

namespace snapfit {

// Round to nearest even; subnormal halves kept; NaN stays NaN, values past 65504 become inf.
inline std::uint16_t float_to_half(float f) {
  std::uint32_t x;
  std::memcpy(&x, &f, 4);
  const auto sign = static_cast<std::uint16_t>((x >> 16) & 0x8000u);
  x &= 0x7fffffffu;
  if (x >= 0x7f800000u) return sign | 0x7c00u | (x > 0x7f800000u ? 0x200u : 0u);  // inf, nan
  if (x >= 0x477ff000u) return sign | 0x7c00u;                                    // rounds past 65504
  if (x < 0x38800000u) {                                                          // below 2^-14: subnormal
    float a;
    std::memcpy(&a, &x, 4);
    return sign | static_cast<std::uint16_t>(std::nearbyint(a * 16777216.0f));  // units of 2^-24
  }
  std::uint32_t h = ((x >> 23) - 112u) << 10 | ((x & 0x7fffffu) >> 13);
  const std::uint32_t rest = x & 0x1fffu;
  if (rest > 0x1000u || (rest == 0x1000u && (h & 1u))) ++h;  // a carry moves into the exponent correctly
  return static_cast<std::uint16_t>(sign | h);
}

}  // namespace snapfit
