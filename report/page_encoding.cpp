#include "report/page_encoding.h"

#include <cstring>

namespace snapfit {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the pages read float32 as little-endian");

std::string base64_encode(const unsigned char* data, std::size_t size) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((size + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 3 <= size; i += 3) {
    const std::uint32_t v = (std::uint32_t(data[i]) << 16) | (std::uint32_t(data[i + 1]) << 8) | data[i + 2];
    for (int shift : {18, 12, 6, 0}) out += kAlphabet[(v >> shift) & 63];
  }
  if (i + 1 == size) {
    const std::uint32_t v = std::uint32_t(data[i]) << 16;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == size) {
    const std::uint32_t v = (std::uint32_t(data[i]) << 16) | (std::uint32_t(data[i + 1]) << 8);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::string float32_base64(const std::vector<float>& values) {
  return base64_encode(reinterpret_cast<const unsigned char*>(values.data()), values.size() * sizeof(float));
}

std::string float32_base64(const std::vector<double>& values) {
  return float32_base64(std::vector<float>(values.begin(), values.end()));
}

}  // namespace snapfit
