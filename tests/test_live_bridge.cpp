// A live session with the device bridge on localhost (jobs/live_session.cpp,
// jobs/bridge_server.cpp), on the shipped default scene at a fixed m': a client at 1 kHz
// for 10 s while the loop keeps its rate; a silent client's wrench fading to zero with
// its pose held; malformed datagrams counted and dropped; a second client refused with
// a message; and a non-finite wrench never sent.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <doctest/doctest.h>
#include <limits>
#include <thread>
#include <vector>

#include "jobs/job_record.h"
#include "scheduler/haptics/assembly_verdict.h"
#include "snapfit/bridge.h"
#include "snapfit/live.h"
#include "tests/test_support.h"

using namespace snapfit;
using namespace std::chrono_literals;

namespace {

// A device program's end of the bridge: a UDP socket that sends states to the session
// and reads what comes back.
struct Client {
  int fd = -1;
  sockaddr_in session{};
  explicit Client(std::uint16_t port) {
    fd = ::socket(AF_INET, SOCK_DGRAM, 0);
    session.sin_family = AF_INET;
    session.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    session.sin_port = htons(port);
  }
  ~Client() { ::close(fd); }
  void send_bytes(const void* data, std::size_t size) const {
    sendto(fd, data, size, 0, reinterpret_cast<const sockaddr*>(&session), sizeof session);
  }
  void send_state(const BodyState& state, std::uint32_t sequence) const {
    const BridgeStateBytes bytes = encode_bridge_state(BridgeState{sequence, state});
    send_bytes(bytes.data(), bytes.size());
  }
  // Every datagram waiting, without blocking.
  std::vector<std::vector<unsigned char>> drain() const {
    std::vector<std::vector<unsigned char>> got;
    unsigned char buffer[2048];
    for (;;) {
      const ssize_t n = recv(fd, buffer, sizeof buffer, MSG_DONTWAIT);
      if (n < 0) return got;
      got.emplace_back(buffer, buffer + n);
    }
  }
  std::vector<BridgeWrench> wrenches() const {
    std::vector<BridgeWrench> out;
    std::string why;
    for (const auto& d : drain())
      if (auto w = decode_bridge_wrench(d.data(), d.size(), why)) out.push_back(*w);
    return out;
  }
};

struct LiveBridge {
  std::unique_ptr<BridgeServer> bridge;
  std::unique_ptr<LiveSession> session;
  Scene scene;
  LiveBridge() {
    scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
    bridge = std::make_unique<BridgeServer>(0, [this](const BodyState& s, std::uint32_t seq) {
      session->set_device_state(s, seq);
    });
    JobRequest request;
    request.modes = 2048;
    request.strategy = "tricubic";
    LiveOptions options;
    options.on_frame = [this](const LiveFrame& f) { bridge->send_frame(f); };
    session = std::make_unique<LiveSession>(scene, request, options);
  }
};

bool all_finite(const BridgeWrench& w) { return w.wrench.force.allFinite() && w.wrench.torque.allFinite(); }

}  // namespace

TEST_CASE("live bridge: a 1 kHz client for 10 s, a silent one, malformed datagrams and a second client") {
  LiveBridge live;
  live.session->start();
  Client client(live.bridge->port());
  BodyState state;
  state.pose = live.scene.part2.pose;

  // 10 s of states at 1 kHz, moving part 2 slowly down towards the hole.
  const auto start = std::chrono::steady_clock::now();
  std::vector<BridgeWrench> received;
  std::uint32_t sequence = 0;
  for (auto next = start; next - start < 10s; next += 1ms) {
    std::this_thread::sleep_until(next);
    state.pose.translation.z() -= 0.0005;
    client.send_state(state, ++sequence);
    for (const BridgeWrench& w : client.wrenches()) received.push_back(w);
  }
  std::this_thread::sleep_for(20ms);
  for (const BridgeWrench& w : client.wrenches()) received.push_back(w);
  const LiveStatus during = live.session->status();
  const BridgeStats stats = live.bridge->stats();
  MESSAGE("10 s at 1 kHz: " << stats.states << " states, " << received.size() << " wrenches back, loop "
                            << during.frames << " frames in " << during.elapsed_s << " s, " << during.misses
                            << " misses");
  CHECK(stats.states >= 9000);  // the client's own sleeps may slip on a busy machine
  // A wrench for every frame the loop ran. The loop ran at the order of 1 kHz: how near it
  // keeps to it is perf/bench_bridge.sh's figure, not this test's (right after the rest of
  // the suite, alone, this machine once ran 83 % of the ticks, and 98 % a minute later).
  CHECK(stats.malformed == 0);
  CHECK(stats.refused == 0);
  CHECK(double(during.frames) >= 0.5 * 10000);
  CHECK(double(received.size()) >= 0.99 * double(during.frames));
  for (const BridgeWrench& w : received) REQUIRE(all_finite(w));
  const LiveFrame now = live.session->latest();
  CHECK(now.sequence == sequence);  // the last state sent is the one the loop reads
  CHECK((now.device.translation - state.pose.translation).norm() < 1e-12);

  // Silent: the pose is held, the wrench fades to zero within late + fade (0.105 s).
  client.drain();
  std::this_thread::sleep_for(300ms);
  const std::vector<BridgeWrench> silent = client.wrenches();
  REQUIRE(silent.size() > 200);
  float previous = 1;
  for (const BridgeWrench& w : silent) {
    CHECK(w.fade <= previous);
    previous = w.fade;
  }
  CHECK((silent.back().flags & bridge_late) != 0);
  CHECK(silent.back().fade == 0.0f);
  CHECK(silent.back().wrench.force.norm() == 0);
  CHECK((live.session->latest().device.translation - state.pose.translation).norm() < 1e-12);

  // Malformed datagrams: counted and dropped, the pose unchanged.
  const unsigned char junk[5] = {1, 2, 3, 4, 5};
  client.send_bytes(junk, sizeof junk);
  BridgeState nan{++sequence, state};
  nan.state.pose.translation.x() = std::numeric_limits<double>::quiet_NaN();
  const BridgeStateBytes nan_bytes = encode_bridge_state(nan);
  client.send_bytes(nan_bytes.data(), nan_bytes.size());
  BridgeStateBytes other_version = encode_bridge_state(BridgeState{++sequence, state});
  other_version[4] = 9;
  client.send_bytes(other_version.data(), other_version.size());
  std::this_thread::sleep_for(50ms);
  CHECK(live.bridge->stats().malformed == 3);
  CHECK(live.session->latest().device.translation.allFinite());

  // A second client while the first is active: refused, with the reason.
  client.send_state(state, ++sequence);
  Client second(live.bridge->port());
  second.send_state(state, 1);
  std::this_thread::sleep_for(50ms);
  bool refused = false;
  for (const auto& d : second.drain())
    if (auto reason = decode_bridge_refusal(d.data(), d.size()))
      refused = reason->find("one device at a time") != std::string::npos;
  CHECK(refused);
  CHECK(live.bridge->stats().refused == 1);

  const LiveStatus end = live.session->stop();
  CHECK(end.sanitised == 0);
  CHECK(end.frames >= during.frames);
}

TEST_CASE("live bridge: a wrench that is not finite goes to the client as zero, flagged") {
  std::vector<std::uint32_t> sequences;
  BridgeServer bridge(0, [&](const BodyState&, std::uint32_t seq) { sequences.push_back(seq); });
  Client client(bridge.port());
  client.send_state(BodyState{}, 5);
  for (int i = 0; i < 100 && sequences.empty(); ++i) std::this_thread::sleep_for(5ms);
  REQUIRE(sequences == std::vector<std::uint32_t>{5});
  LiveFrame frame;
  frame.sequence = 5;
  frame.sent.force = Eigen::Vector3d(1, std::numeric_limits<double>::infinity(), 0);
  bridge.send_frame(frame);
  std::this_thread::sleep_for(20ms);
  const std::vector<BridgeWrench> got = client.wrenches();
  REQUIRE(got.size() == 1);
  CHECK(got[0].sequence == 5);
  CHECK(got[0].wrench.force.norm() == 0);
  CHECK((got[0].flags & bridge_sanitised) != 0);
}

TEST_CASE("live session: a recording becomes a job result with the recorded frames, bad requests are named") {
  const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  JobRequest request;
  request.modes = 2048;
  request.strategy = "tricubic";
  LiveSession session(scene, request);
  CHECK(session.prepared().tuning.chosen_modes == 2048);
  session.start();
  session.start_recording();
  std::this_thread::sleep_for(300ms);
  const JobResult recorded = session.stop_recording();
  REQUIRE(recorded.loop);
  CHECK(recorded.loop->frames > 100);
  CHECK(recorded.loop->log.size() == recorded.loop->frames);
  REQUIRE(recorded.session);
  REQUIRE(recorded.part2.mesh);
  // The device 5 mm off: the part follows; a reset puts both back.
  BodyState moved;
  moved.pose = scene.part2.pose;
  moved.pose.translation.x() += 5;
  session.set_device_state(moved);
  std::this_thread::sleep_for(400ms);
  const double followed = (session.status().part.translation - scene.part2.pose.translation).norm();
  MESSAGE("the part followed the device " << followed << " mm of 5");
  CHECK(followed > 2);
  session.reset();
  std::this_thread::sleep_for(50ms);
  CHECK((session.latest().device.translation - scene.part2.pose.translation).norm() < 1e-12);
  CHECK((session.status().part.translation - scene.part2.pose.translation).norm() < 1);
  const LiveStatus end = session.stop();
  // The verdict, with part 2 back near its start ~30 mm above the fit: its surface is
  // measured afresh at the final pose, with the judge `snapfit run` uses.
  const AssemblyJudge judge(*recorded.part2.mesh, *scene.assembled_pose, recorded.session->position_tolerance,
                            recorded.session->angle_tolerance_deg);
  CHECK(end.evaluated);
  CHECK(!end.assembled);
  CHECK(end.surface_deviation > 20);
  CHECK(end.surface_deviation == doctest::Approx(judge.surface(end.part).distance).epsilon(1e-12));
  CHECK(recorded.final_surface_deviation == recorded.session->surface_deviation);
  CHECK(recorded.final_surface_deviation > 20);

  Scene vps = scene;
  vps.method = Method::vps;
  CHECK(test::error_of([&] { LiveSession s(vps); }).find("vps") != std::string::npos);
  JobRequest simulated;
  simulated.simulated_time = true;
  CHECK(test::error_of([&] { LiveSession s(scene, simulated); }).find("simulated") != std::string::npos);
}
