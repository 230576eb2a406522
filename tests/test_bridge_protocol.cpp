// snapfit/bridge.h: the bridge's datagrams, byte for byte against the documented layout
// (read back by hand here), and every malformed kind refused with its reason.
#include <cmath>
#include <cstring>
#include <doctest/doctest.h>
#include <limits>

#include "snapfit/bridge.h"

using namespace snapfit;

namespace {

template <typename T>
T read_le(const unsigned char* at) {  // this test runs on little-endian hosts
  T value;
  std::memcpy(&value, at, sizeof(T));
  return value;
}

BridgeState sample_state() {
  BridgeState s;
  s.sequence = 123456;
  s.state.pose.translation = Eigen::Vector3d(1.5, -2.25, 30);
  s.state.pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 3).normalized()));
  s.state.velocity = Eigen::Vector3d(0.1, 0.2, -0.3);
  s.state.angular_velocity = Eigen::Vector3d(-1, 0, 2);
  return s;
}

}  // namespace

TEST_CASE("bridge protocol: a state's bytes are the documented layout, and decode back") {
  const BridgeState s = sample_state();
  const BridgeStateBytes bytes = encode_bridge_state(s);
  REQUIRE(bytes.size() == 116);
  CHECK(std::memcmp(bytes.data(), "SNFB", 4) == 0);
  CHECK(read_le<std::uint16_t>(bytes.data() + 4) == 1);  // version
  CHECK(read_le<std::uint16_t>(bytes.data() + 6) == 1);  // kind: state
  CHECK(read_le<std::uint32_t>(bytes.data() + 8) == 123456);
  CHECK(read_le<double>(bytes.data() + 12) == 1.5);
  CHECK(read_le<double>(bytes.data() + 28) == 30);
  CHECK(read_le<double>(bytes.data() + 36) == s.state.pose.rotation.w());
  CHECK(read_le<double>(bytes.data() + 60) == s.state.pose.rotation.z());
  CHECK(read_le<double>(bytes.data() + 68) == 0.1);
  CHECK(read_le<double>(bytes.data() + 108) == 2);
  std::string why;
  const auto back = decode_bridge_state(bytes.data(), bytes.size(), why);
  REQUIRE(back);
  CHECK(why.empty());
  CHECK(back->sequence == s.sequence);
  CHECK(back->state.pose.translation == s.state.pose.translation);
  CHECK(back->state.pose.rotation.isApprox(s.state.pose.rotation, 1e-15));
  CHECK(back->state.velocity == s.state.velocity);
  CHECK(back->state.angular_velocity == s.state.angular_velocity);
}

TEST_CASE("bridge protocol: a wrench and a refusal round-trip") {
  BridgeWrench w;
  w.sequence = 7;
  w.frame = 99;
  w.wrench.force = Eigen::Vector3d(1, -2, 3);
  w.wrench.torque = Eigen::Vector3d(0.01, 0.02, -0.03);
  w.energy = -4.5;
  w.fade = 0.25f;
  w.flags = bridge_late | bridge_contact;
  const BridgeWrenchBytes bytes = encode_bridge_wrench(w);
  REQUIRE(bytes.size() == 80);
  CHECK(read_le<std::uint16_t>(bytes.data() + 6) == 2);
  CHECK(read_le<std::uint32_t>(bytes.data() + 12) == 99);
  CHECK(read_le<double>(bytes.data() + 16) == 1);
  CHECK(read_le<double>(bytes.data() + 64) == -4.5);
  CHECK(read_le<float>(bytes.data() + 72) == 0.25f);
  CHECK(read_le<std::uint32_t>(bytes.data() + 76) == (bridge_late | bridge_contact));
  std::string why;
  const auto back = decode_bridge_wrench(bytes.data(), bytes.size(), why);
  REQUIRE(back);
  CHECK(back->wrench.force == w.wrench.force);
  CHECK(back->wrench.torque == w.wrench.torque);
  CHECK(back->fade == 0.25f);
  const std::string refusal = encode_bridge_refusal("one device at a time");
  const auto reason =
      decode_bridge_refusal(reinterpret_cast<const unsigned char*>(refusal.data()), refusal.size());
  REQUIRE(reason);
  CHECK(*reason == "one device at a time");
}

TEST_CASE("bridge protocol: short, foreign, other-version, other-kind, NaN and non-unit states are refused") {
  const BridgeStateBytes good = encode_bridge_state(sample_state());
  std::string why;
  CHECK_FALSE(decode_bridge_state(good.data(), good.size() - 1, why));
  CHECK(why.find("bytes") != std::string::npos);
  BridgeStateBytes bad = good;
  bad[0] = 'X';
  CHECK_FALSE(decode_bridge_state(bad.data(), bad.size(), why));
  CHECK(why.find("magic") != std::string::npos);
  bad = good;
  bad[4] = 2;
  CHECK_FALSE(decode_bridge_state(bad.data(), bad.size(), why));
  CHECK(why.find("version 2") != std::string::npos);
  const BridgeWrenchBytes wrench = encode_bridge_wrench({});
  CHECK_FALSE(decode_bridge_state(wrench.data(), wrench.size(), why));
  CHECK(why.find("kind 2") != std::string::npos);
  BridgeState nan = sample_state();
  nan.state.velocity.x() = std::numeric_limits<double>::quiet_NaN();
  const BridgeStateBytes nan_bytes = encode_bridge_state(nan);
  CHECK_FALSE(decode_bridge_state(nan_bytes.data(), nan_bytes.size(), why));
  CHECK(why.find("finite") != std::string::npos);
  BridgeState stretched = sample_state();
  stretched.state.pose.rotation.coeffs() *= 2;
  const BridgeStateBytes stretched_bytes = encode_bridge_state(stretched);
  CHECK_FALSE(decode_bridge_state(stretched_bytes.data(), stretched_bytes.size(), why));
  CHECK(why.find("orientation") != std::string::npos);
}
