#pragma once
// FNV-1a 64-bit hash: cache keys and payload checksums. Not cryptographic; it detects
// torn writes, bit rot and key changes, which is all a local cache needs.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>

namespace snapfit {

inline std::uint64_t fnv1a64(const void* data, std::size_t size, std::uint64_t hash = 14695981039346656037ull) {
  const unsigned char* bytes = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < size; ++i) {
    hash ^= bytes[i];
    hash *= 1099511628211ull;
  }
  return hash;
}

inline std::uint64_t fnv1a64(const std::string& text) { return fnv1a64(text.data(), text.size()); }

inline std::string hex64(std::uint64_t value) {
  char buffer[17];
  std::snprintf(buffer, sizeof buffer, "%016llx", static_cast<unsigned long long>(value));
  return buffer;
}

}  // namespace snapfit
