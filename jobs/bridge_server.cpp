// snapfit/bridge.h BridgeServer: the device bridge's UDP socket on 127.0.0.1, a
// receiving thread, and the wrench sent from the loop's thread.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <mutex>
#include <thread>

#include "snapfit/bridge.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

using Clock = std::chrono::steady_clock;

// An IPv4 address and port in one word (0: none), so the loop's thread reads the
// client without a lock.
std::uint64_t pack_address(const sockaddr_in& a) {
  return (std::uint64_t(ntohl(a.sin_addr.s_addr)) << 16 | ntohs(a.sin_port)) | (1ull << 48);
}

sockaddr_in unpack_address(std::uint64_t packed) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(std::uint32_t(packed >> 16));
  a.sin_port = htons(std::uint16_t(packed & 0xffff));
  return a;
}

std::string address_text(std::uint64_t packed) {
  if (!packed) return "";
  const sockaddr_in a = unpack_address(packed);
  char ip[INET_ADDRSTRLEN] = {};
  inet_ntop(AF_INET, &a.sin_addr, ip, sizeof ip);
  return std::string(ip) + ":" + std::to_string(ntohs(a.sin_port));
}

}  // namespace

struct BridgeServer::State {
  int socket = -1;
  std::uint16_t port = 0;
  std::function<void(const BodyState&, std::uint32_t)> on_state;
  double release_s = 1;
  std::atomic<bool> quit{false};
  std::thread thread;
  std::atomic<std::uint64_t> client{0};  // pack_address, 0: none
  std::atomic<std::uint64_t> wrenches{0};
  mutable std::mutex mutex;  // guards the stats below and the client's last state time
  BridgeStats stats;
  Clock::time_point client_seen;

  void receive();
  void handle(const unsigned char* data, std::size_t size, const sockaddr_in& from);
};

void BridgeServer::State::handle(const unsigned char* data, std::size_t size, const sockaddr_in& from) {
  const std::uint64_t sender = pack_address(from);
  std::string why;
  const std::optional<BridgeState> state = decode_bridge_state(data, size, why);
  const Clock::time_point now = Clock::now();
  std::unique_lock<std::mutex> lock(mutex);
  if (!state) {
    ++stats.malformed;
    stats.last_malformed = why;
    return;
  }
  const std::uint64_t current = client.load();
  const bool released = current && std::chrono::duration<double>(now - client_seen).count() > release_s;
  if (current && current != sender && !released) {
    ++stats.refused;
    const std::string refusal = encode_bridge_refusal(
        "snapfit: the bridge has a client (" + address_text(current) + "); one device at a time");
    lock.unlock();
    sendto(socket, refusal.data(), refusal.size(), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&from),
           sizeof from);
    return;
  }
  client = sender;
  client_seen = now;
  ++stats.states;
  lock.unlock();
  on_state(state->state, state->sequence);
}

void BridgeServer::State::receive() {
  unsigned char buffer[2048];
  while (!quit) {
    sockaddr_in from{};
    socklen_t length = sizeof from;
    const ssize_t got =
        recvfrom(socket, buffer, sizeof buffer, 0, reinterpret_cast<sockaddr*>(&from), &length);
    if (got < 0) continue;  // the receive timeout: look at `quit` again
    if (length != sizeof from || from.sin_family != AF_INET) continue;
    handle(buffer, std::size_t(got), from);
  }
}

BridgeServer::BridgeServer(std::uint16_t port, std::function<void(const BodyState&, std::uint32_t)> on_state,
                           double release_s)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.on_state = std::move(on_state);
  s.release_s = release_s;
  s.socket = ::socket(AF_INET, SOCK_DGRAM, 0);
  if (s.socket < 0) throw Error(std::string("bridge: cannot open a UDP socket: ") + std::strerror(errno));
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(port);
  if (bind(s.socket, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
    const std::string reason = std::strerror(errno);
    ::close(s.socket);
    throw Error("bridge: cannot bind UDP 127.0.0.1:" + std::to_string(port) + ": " + reason);
  }
  socklen_t length = sizeof address;
  getsockname(s.socket, reinterpret_cast<sockaddr*>(&address), &length);
  s.port = ntohs(address.sin_port);
  timeval timeout{0, 100000};  // the receiving thread looks at `quit` every 0.1 s
  setsockopt(s.socket, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
  s.thread = std::thread([&s] { s.receive(); });
}

BridgeServer::~BridgeServer() {
  state_->quit = true;
  state_->thread.join();
  ::close(state_->socket);
}

std::uint16_t BridgeServer::port() const { return state_->port; }

void BridgeServer::send_frame(const LiveFrame& frame) {
  const std::uint64_t client = state_->client.load();
  if (!client) return;
  BridgeWrench w;
  w.sequence = frame.sequence;
  w.frame = std::uint32_t(frame.frame);
  w.wrench = frame.sent;
  w.energy = std::isfinite(frame.energy) ? frame.energy : 0;
  w.fade = frame.fade;
  w.flags = (frame.late ? bridge_late : 0u) | (frame.contact_depth > 0 ? bridge_contact : 0u) |
            (frame.flags ? bridge_flagged : 0u);
  if (!w.wrench.force.allFinite() || !w.wrench.torque.allFinite()) {  // never a NaN to a hand
    w.wrench = Wrench{};
    w.flags |= bridge_sanitised;
  }
  const BridgeWrenchBytes bytes = encode_bridge_wrench(w);
  const sockaddr_in to = unpack_address(client);
  if (sendto(state_->socket, bytes.data(), bytes.size(), MSG_DONTWAIT, reinterpret_cast<const sockaddr*>(&to),
             sizeof to) == ssize_t(bytes.size()))
    ++state_->wrenches;
}

BridgeStats BridgeServer::stats() const {
  const std::lock_guard<std::mutex> lock(state_->mutex);
  BridgeStats s = state_->stats;
  s.wrenches = state_->wrenches.load();
  s.client = address_text(state_->client.load());
  return s;
}

}  // namespace snapfit
