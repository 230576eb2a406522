#pragma once
// Whether this machine stores numbers little-endian first: the byte order files and the
// device bridge's messages are written in, swapped on a big-endian host.
#include <cstdint>
#include <cstring>

namespace snapfit {

inline bool host_is_little_endian() {
  const std::uint16_t one = 1;
  unsigned char first = 0;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace snapfit
