#pragma once
// The device bridge's protocol (docs/haptics.md "The device bridge"): how a program that
// drives a haptic device, in any language, takes part in a live session (live.h) over
// UDP on localhost. Every frame the program sends the device's state; every frame of
// the haptic loop the session sends back the wrench to render. Datagrams are binary,
// little-endian, fixed-size, each starting with the magic "SNFB" and the version.
//
//   state   (client -> session, 116 bytes): magic, version u16, kind u16 = 1, sequence u32,
//            position[3] f64 (scene units), orientation[4] f64 (w, x, y, z), velocity[3] f64
//            (scene units / s), angular_velocity[3] f64 (rad / s); all in part 1's frame
//   wrench  (session -> client, 80 bytes): magic, version u16, kind u16 = 2, sequence u32 (the
//            last state's), frame u32, force[3] f64 (N), torque[3] f64 (N m), energy f64,
//            fade f32 (1: fresh, 0: faded out), flags u32
//   refusal (session -> client, 12 + n bytes): magic, version u16, kind u16 = 3, length u32,
//            the reason in UTF-8
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "snapfit/haptic_device.h"
#include "snapfit/live.h"

namespace snapfit {

constexpr std::uint16_t kBridgeVersion = 1;
constexpr std::size_t kBridgeStateBytes = 116;
constexpr std::size_t kBridgeWrenchBytes = 80;

enum class BridgeKind : std::uint16_t { state = 1, wrench = 2, refusal = 3 };

// Bits of BridgeWrench::flags.
enum BridgeFlags : std::uint32_t {
  bridge_late = 1u << 0,      // the last state is older than the session's `late` time: held, fading
  bridge_contact = 1u << 1,   // the rigid contact touched this frame
  bridge_flagged = 1u << 2,   // the query was flagged (outside the grid): no geometric wrench
  bridge_sanitised = 1u << 3, // the wrench was not finite and was replaced by zero
};

struct BridgeState {
  std::uint32_t sequence = 0;
  BodyState state;
};

struct BridgeWrench {
  std::uint32_t sequence = 0;  // of the last state the session used
  std::uint32_t frame = 0;
  Wrench wrench;
  double energy = 0;
  float fade = 1;
  std::uint32_t flags = 0;
};

using BridgeStateBytes = std::array<unsigned char, kBridgeStateBytes>;
using BridgeWrenchBytes = std::array<unsigned char, kBridgeWrenchBytes>;

BridgeStateBytes encode_bridge_state(const BridgeState& state);
BridgeWrenchBytes encode_bridge_wrench(const BridgeWrench& wrench);
std::string encode_bridge_refusal(const std::string& reason);

// The datagram as a state, or why it is not one ("" in `why` when it is): the wrong
// size, magic, version or kind, a non-finite number, or an orientation far from unit
// length (it is normalised when near).
std::optional<BridgeState> decode_bridge_state(const unsigned char* data, std::size_t size, std::string& why);
std::optional<BridgeWrench> decode_bridge_wrench(const unsigned char* data, std::size_t size, std::string& why);
// The reason of a refusal datagram, or nothing.
std::optional<std::string> decode_bridge_refusal(const unsigned char* data, std::size_t size);

// The session's end of the bridge: a UDP socket on 127.0.0.1. The first sender of a
// valid state is the client; a datagram from anyone else while it is active (a state
// within `release_s`) is answered with a refusal and counted; a client silent for
// longer is released. Malformed datagrams are counted and dropped.
struct BridgeStats {
  std::uint64_t states = 0;      // valid states from the client
  std::uint64_t malformed = 0;   // datagrams dropped as malformed
  std::uint64_t refused = 0;     // datagrams from a second client, answered with a refusal
  std::uint64_t wrenches = 0;    // wrench datagrams sent
  std::string client;            // "127.0.0.1:PORT" of the client; "" when none
  std::string last_malformed;    // why the last malformed datagram was dropped
};

class BridgeServer {
 public:
  // Binds 127.0.0.1:`port` (0: a free port) and receives on its own thread, handing each
  // valid state of the client to `on_state` (LiveSession::set_device_state). Throws
  // snapfit::Error naming the port when it cannot be bound.
  BridgeServer(std::uint16_t port, std::function<void(const BodyState&, std::uint32_t sequence)> on_state,
               double release_s = 1.0);
  ~BridgeServer();
  BridgeServer(const BridgeServer&) = delete;
  BridgeServer& operator=(const BridgeServer&) = delete;

  std::uint16_t port() const;
  // The frame's wrench to the client, if there is one (from LiveOptions::on_frame, on
  // the loop's thread: one non-blocking send, no allocation).
  void send_frame(const LiveFrame& frame);
  BridgeStats stats() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace snapfit
