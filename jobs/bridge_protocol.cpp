// snapfit/bridge.h: the device bridge's datagrams, little-endian, fixed-size.
#include <cmath>
#include <cstring>

#include "core/host_endian.h"
#include "snapfit/bridge.h"

namespace snapfit {
namespace {

constexpr unsigned char kMagic[4] = {'S', 'N', 'F', 'B'};
constexpr std::size_t kHeaderBytes = 8;  // magic, version, kind

static_assert(sizeof(double) == 8 && sizeof(float) == 4, "the protocol's numbers are IEEE 754");

// Little-endian writer and reader (the host order on every machine snapfit runs on is
// checked at run time, so a big-endian host swaps).
template <typename T>
void put(unsigned char*& at, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (!host_is_little_endian())
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  std::memcpy(at, bytes, sizeof(T));
  at += sizeof(T);
}

template <typename T>
T get(const unsigned char*& at) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, at, sizeof(T));
  if (!host_is_little_endian())
    for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(bytes[i], bytes[sizeof(T) - 1 - i]);
  at += sizeof(T);
  T value;
  std::memcpy(&value, bytes, sizeof(T));
  return value;
}

void put_header(unsigned char*& at, BridgeKind kind) {
  std::memcpy(at, kMagic, 4);
  at += 4;
  put<std::uint16_t>(at, kBridgeVersion);
  put<std::uint16_t>(at, static_cast<std::uint16_t>(kind));
}

void put_vector(unsigned char*& at, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) put<double>(at, v[i]);
}

Eigen::Vector3d get_vector(const unsigned char*& at) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = get<double>(at);
  return v;
}

// The header of a datagram of `kind` and `expected` bytes (0: at least the header).
bool check_header(const unsigned char* data, std::size_t size, BridgeKind kind, std::size_t expected,
                  std::string& why) {
  if (size < kHeaderBytes || std::memcmp(data, kMagic, 4) != 0) {
    why = "not a bridge datagram (no SNFB magic)";
    return false;
  }
  const unsigned char* at = data + 4;
  const auto version = get<std::uint16_t>(at);
  const auto got = get<std::uint16_t>(at);
  if (version != kBridgeVersion) {
    why = "protocol version " + std::to_string(version) + ", this session speaks " + std::to_string(kBridgeVersion);
    return false;
  }
  if (got != static_cast<std::uint16_t>(kind)) {
    why = "kind " + std::to_string(got) + " where " + std::to_string(static_cast<int>(kind)) + " was expected";
    return false;
  }
  if (expected && size != expected) {
    why = std::to_string(size) + " bytes where " + std::to_string(expected) + " were expected";
    return false;
  }
  return true;
}

}  // namespace

BridgeStateBytes encode_bridge_state(const BridgeState& s) {
  BridgeStateBytes bytes{};
  unsigned char* at = bytes.data();
  put_header(at, BridgeKind::state);
  put<std::uint32_t>(at, s.sequence);
  put_vector(at, s.state.pose.translation);
  const Eigen::Quaterniond& q = s.state.pose.rotation;
  for (double c : {q.w(), q.x(), q.y(), q.z()}) put<double>(at, c);
  put_vector(at, s.state.velocity);
  put_vector(at, s.state.angular_velocity);
  return bytes;
}

BridgeWrenchBytes encode_bridge_wrench(const BridgeWrench& w) {
  BridgeWrenchBytes bytes{};
  unsigned char* at = bytes.data();
  put_header(at, BridgeKind::wrench);
  put<std::uint32_t>(at, w.sequence);
  put<std::uint32_t>(at, w.frame);
  put_vector(at, w.wrench.force);
  put_vector(at, w.wrench.torque);
  put<double>(at, w.energy);
  put<float>(at, w.fade);
  put<std::uint32_t>(at, w.flags);
  return bytes;
}

std::string encode_bridge_refusal(const std::string& reason) {
  std::string bytes(12 + reason.size(), '\0');
  unsigned char* at = reinterpret_cast<unsigned char*>(bytes.data());
  put_header(at, BridgeKind::refusal);
  put<std::uint32_t>(at, static_cast<std::uint32_t>(reason.size()));
  std::memcpy(at, reason.data(), reason.size());
  return bytes;
}

std::optional<BridgeState> decode_bridge_state(const unsigned char* data, std::size_t size, std::string& why) {
  why.clear();
  if (!check_header(data, size, BridgeKind::state, kBridgeStateBytes, why)) return std::nullopt;
  const unsigned char* at = data + kHeaderBytes;
  BridgeState s;
  s.sequence = get<std::uint32_t>(at);
  s.state.pose.translation = get_vector(at);
  double q[4];
  for (double& c : q) c = get<double>(at);
  s.state.velocity = get_vector(at);
  s.state.angular_velocity = get_vector(at);
  const Eigen::Quaterniond turn(q[0], q[1], q[2], q[3]);
  const bool finite = s.state.pose.translation.allFinite() && turn.coeffs().allFinite() &&
                      s.state.velocity.allFinite() && s.state.angular_velocity.allFinite();
  if (!finite) {
    why = "a number that is not finite";
    return std::nullopt;
  }
  if (std::abs(turn.norm() - 1) > 1e-3) {
    why = "an orientation of length " + std::to_string(turn.norm()) + " (a unit quaternion w, x, y, z is expected)";
    return std::nullopt;
  }
  s.state.pose.rotation = turn.normalized();
  return s;
}

std::optional<BridgeWrench> decode_bridge_wrench(const unsigned char* data, std::size_t size, std::string& why) {
  why.clear();
  if (!check_header(data, size, BridgeKind::wrench, kBridgeWrenchBytes, why)) return std::nullopt;
  const unsigned char* at = data + kHeaderBytes;
  BridgeWrench w;
  w.sequence = get<std::uint32_t>(at);
  w.frame = get<std::uint32_t>(at);
  w.wrench.force = get_vector(at);
  w.wrench.torque = get_vector(at);
  w.energy = get<double>(at);
  w.fade = get<float>(at);
  w.flags = get<std::uint32_t>(at);
  return w;
}

std::optional<std::string> decode_bridge_refusal(const unsigned char* data, std::size_t size) {
  std::string why;
  if (!check_header(data, size, BridgeKind::refusal, 0, why) || size < 12) return std::nullopt;
  const unsigned char* at = data + kHeaderBytes;
  const auto length = get<std::uint32_t>(at);
  if (size != 12 + std::size_t(length)) return std::nullopt;
  return std::string(reinterpret_cast<const char*>(at), length);
}

}  // namespace snapfit
