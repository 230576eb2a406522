#pragma once
// Plain values and arrays of them, appended to a cache payload in order and read back
// with bounds checks (io/cache_file.h holds the payload): an array is its u64 length and
// then its elements. A read past the end or of an impossible length clears `ok`; the
// caller then treats the entry as absent. Eigen's fixed-size 3-vectors go as their
// three coefficients.
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

namespace snapfit {

struct PayloadWriter {
  std::vector<unsigned char> bytes;

  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const auto* p = reinterpret_cast<const unsigned char*>(&value);
    bytes.insert(bytes.end(), p, p + sizeof(T));
  }
  template <typename T, typename Allocator>
  void put_array(const std::vector<T, Allocator>& v) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<std::uint64_t>(v.size());
    const auto* p = reinterpret_cast<const unsigned char*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(T));
  }
  template <typename Vector3>
  void put_vector3(const Vector3& v) {
    for (int a = 0; a < 3; ++a) put(v[a]);
  }
};

struct PayloadReader {
  const std::vector<unsigned char>& bytes;
  std::size_t at = 0;
  bool ok = true;

  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value{};
    if (!ok || bytes.size() - at < sizeof(T)) return ok = false, value;
    std::memcpy(&value, bytes.data() + at, sizeof(T));
    at += sizeof(T);
    return value;
  }
  template <typename T, typename Allocator = std::allocator<T>>
  std::vector<T, Allocator> get_array() {
    const std::uint64_t n = get<std::uint64_t>();
    if (!ok || (bytes.size() - at) / sizeof(T) < n) return ok = false, std::vector<T, Allocator>();
    std::vector<T, Allocator> v(n);
    std::memcpy(v.data(), bytes.data() + at, n * sizeof(T));
    at += n * sizeof(T);
    return v;
  }
  template <typename Vector3>
  Vector3 get_vector3() {
    Vector3 v;
    for (int a = 0; a < 3; ++a) v[a] = get<std::decay_t<decltype(v[0])>>();
    return v;
  }
  bool finished() const { return ok && at == bytes.size(); }
};

}  // namespace snapfit
