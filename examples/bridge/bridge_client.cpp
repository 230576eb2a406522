// A device program's end of snapfit's device bridge, in C++ (snapfit/bridge.h for the
// datagrams; no device SDK): plays a scene's scripted trajectory as the device's motion
// at a fixed rate, renders nothing, and prints what came back as one JSON line (states
// sent, wrenches received, round-trip p50 and p99 from a state to the first wrench
// computed from it, the last wrench).
//
//   snapfit_bridge_client PORT SCENE [RATE_HZ [SETTLE_S]]
//
// A real device's loop reads its handle where this one interpolates the trajectory, and
// renders each wrench's force and torque (N, N m in part 1's frame).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <snapfit/snapfit.h>
#include <thread>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;

// The trajectory's pose at `t`: positions linear, rotations slerped, held at the ends.
snapfit::Pose pose_at(const std::vector<snapfit::Keyframe>& k, double t) {
  if (t <= k.front().time_s) return k.front().pose;
  for (std::size_t i = 1; i < k.size(); ++i) {
    if (t > k[i].time_s) continue;
    const double f = (t - k[i - 1].time_s) / (k[i].time_s - k[i - 1].time_s);
    snapfit::Pose p;
    p.translation = (1 - f) * k[i - 1].pose.translation + f * k[i].pose.translation;
    p.rotation = k[i - 1].pose.rotation.slerp(f, k[i].pose.rotation);
    return p;
  }
  return k.back().pose;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(std::max(0.0, std::ceil(q * double(v.size())) - 1)))];
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s PORT SCENE [RATE_HZ [SETTLE_S]]\n", argv[0]);
    return 2;
  }
  try {
    const int port = std::atoi(argv[1]);
    const snapfit::Scene scene = snapfit::load_scene(argv[2]);
    const double rate = argc >= 4 ? std::atof(argv[3]) : 1000;
    const double settle = argc >= 5 ? std::atof(argv[4]) : 1.0;
    const auto& keys = scene.trajectory.keyframes;
    if (keys.empty() || !(rate > 0)) throw snapfit::Error("the scene needs a trajectory and the rate must be > 0");

    const int fd = socket(AF_INET, SOCK_DGRAM, 0);
    sockaddr_in session{};
    session.sin_family = AF_INET;
    session.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    session.sin_port = htons(std::uint16_t(port));

    const double duration = keys.back().time_s - keys.front().time_s + settle;
    std::map<std::uint32_t, Clock::time_point> sent_at;
    std::vector<double> round_trips;
    std::size_t states = 0, wrenches = 0;
    snapfit::BridgeWrench last;
    const Clock::time_point start = Clock::now();
    // Between sends the client waits on the socket, so a wrench is timed when it arrives.
    const auto receive_until = [&](Clock::time_point until) {
      unsigned char buffer[2048];
      for (;;) {
        const auto left = std::chrono::duration_cast<std::chrono::nanoseconds>(until - Clock::now()).count();
        pollfd p{fd, POLLIN, 0};
        const timespec wait{time_t(left / 1000000000), long(left % 1000000000)};  // not rounded to a millisecond
        if (left <= 0 || ppoll(&p, 1, &wait, nullptr) <= 0) return true;
        const ssize_t n = recv(fd, buffer, sizeof buffer, MSG_DONTWAIT);
        if (n <= 0) continue;
        if (auto reason = snapfit::decode_bridge_refusal(buffer, std::size_t(n))) {
          std::printf("{\"refused\": \"%s\"}\n", reason->c_str());
          return false;
        }
        std::string why;
        const auto w = snapfit::decode_bridge_wrench(buffer, std::size_t(n), why);
        if (!w) continue;
        ++wrenches;
        last = *w;
        const auto at = sent_at.find(w->sequence);
        if (at == sent_at.end()) continue;  // a later wrench from a state already timed
        round_trips.push_back(1e3 * std::chrono::duration<double>(Clock::now() - at->second).count());
        sent_at.erase(sent_at.begin(), std::next(at));  // and the states the loop skipped
      }
    };
    for (;; ++states) {
      const Clock::time_point due = start + std::chrono::duration_cast<Clock::duration>(
                                                std::chrono::duration<double>(double(states) / rate));
      if (!receive_until(due)) return 3;
      const double t = std::chrono::duration<double>(Clock::now() - start).count();
      if (t > duration) break;
      snapfit::BridgeState state;
      state.sequence = std::uint32_t(states + 1);
      state.state.pose = pose_at(keys, keys.front().time_s + t);
      const snapfit::BridgeStateBytes bytes = snapfit::encode_bridge_state(state);
      sent_at[state.sequence] = Clock::now();
      sendto(fd, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr*>(&session), sizeof session);
    }
    close(fd);
    std::printf(
        "{\"states\": %zu, \"wrenches\": %zu, \"round_trip_ms_p50\": %.4f, \"round_trip_ms_p99\": %.4f, "
        "\"last_force\": [%.6g, %.6g, %.6g], \"last_fade\": %.3g}\n",
        states, wrenches, percentile(round_trips, 0.5), percentile(round_trips, 0.99), last.wrench.force.x(),
        last.wrench.force.y(), last.wrench.force.z(), last.fade);
    return 0;
  } catch (const snapfit::Error& e) {
    std::fprintf(stderr, "snapfit_bridge_client: %s\n", e.what());
    return 1;
  }
}
