#include "cli/live_server.h"

#include <httplib.h>

#include <chrono>
#include <cmath>
#include <map>
#include <mutex>
#include <nlohmann/json.hpp>
#include <thread>

#include "report/run_page.h"
#include "report/run_report.h"
#include "snapfit/error.h"
#include "snapfit/pose_json.h"

namespace snapfit::cli {
namespace {

nlohmann::json vector_json(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

nlohmann::json wrench_json(const Wrench& w) { return {{"force", vector_json(w.force)}, {"torque", vector_json(w.torque)}}; }

nlohmann::json state_json(const LiveFrame& f, const LiveStatus& s, const BridgeStats& b) {
  return {{"frame",
           {{"frame", f.frame},
            {"time_s", f.time_s},
            {"sequence", f.sequence},
            {"device", pose_json<nlohmann::json>(f.device)},
            {"part", pose_json<nlohmann::json>(f.part)},
            {"energy", std::isfinite(f.energy) ? f.energy : 0.0},
            {"geometric", wrench_json(f.geometric)},
            {"contact", wrench_json(f.contact)},
            {"contact_depth", f.contact_depth},
            {"sent", wrench_json(f.sent)},
            {"fade", f.fade},
            {"late", f.late},
            {"modes", f.modes},
            {"frame_ms", f.frame_ms},
            {"flags", f.flags},
            {"missed", f.missed}}},
          {"status",
           {{"frames", s.frames},
            {"misses", s.misses},
            {"sanitised", s.sanitised},
            {"elapsed_s", s.elapsed_s},
            {"recording", s.recording},
            {"evaluated", s.evaluated},
            {"assembled", s.assembled},
            {"position_error", s.position_error},
            {"angle_error_deg", s.angle_error_deg},
            {"surface_deviation", s.surface_deviation}}},
          {"bridge",
           {{"states", b.states},
            {"malformed", b.malformed},
            {"refused", b.refused},
            {"wrenches", b.wrenches},
            {"client", b.client},
            {"last_malformed", b.last_malformed}}}};
}

// `count` finite numbers under `key`, or why not.
bool read_numbers(const nlohmann::json& body, const char* key, std::size_t count, double* out, std::string& why) {
  if (!body.contains(key)) {
    why = std::string("'") + key + "' is missing";
    return false;
  }
  const nlohmann::json& v = body[key];
  if (!v.is_array() || v.size() != count) {
    why = std::string("'") + key + "' must be an array of " + std::to_string(count) + " numbers";
    return false;
  }
  for (std::size_t i = 0; i < count; ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>())) {
      why = std::string("'") + key + "' holds something that is not a finite number";
      return false;
    }
    out[i] = v[i].get<double>();
  }
  return true;
}

// The device's pose from POST /device's body, or why it is not one.
std::optional<Pose> device_pose(const std::string& text, std::string& why) {
  const nlohmann::json body = nlohmann::json::parse(text, nullptr, false);
  if (body.is_discarded() || !body.is_object()) {
    why = "the body is not a JSON object";
    return std::nullopt;
  }
  double p[3], q[4];
  if (!read_numbers(body, "position", 3, p, why) || !read_numbers(body, "quaternion", 4, q, why))
    return std::nullopt;
  const Eigen::Quaterniond turn(q[0], q[1], q[2], q[3]);
  if (!(turn.norm() > 1e-9)) {
    why = "'quaternion' is zero";
    return std::nullopt;
  }
  Pose pose;
  pose.translation = Eigen::Vector3d(p[0], p[1], p[2]);
  pose.rotation = turn.normalized();
  return pose;
}

void reply(httplib::Response& res, int status, const nlohmann::json& body) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

}  // namespace

struct LiveHttpServer::State {
  State(LiveSession& s, const BridgeServer& b, std::string p, std::filesystem::path base)
      : session(s), bridge(b), page(std::move(p)), record_base(std::move(base)) {}
  LiveSession& session;
  const BridgeServer& bridge;
  std::string page;
  std::filesystem::path record_base;
  httplib::Server server;
  std::thread thread;
  std::uint16_t port = 0;
  std::atomic<bool> quit{false};
  std::mutex record_mutex;  // one recording written at a time
  int recordings = 0;
  std::chrono::steady_clock::time_point record_start;
  // The POST handlers by path. A POST with no body at all (no Content-Length, not
  // chunked: `curl -X POST URL`) is refused with 400 by the server library before
  // routing, so these answer it first, as a POST with an empty body.
  std::map<std::string, httplib::Server::Handler> posts;

  void post(const std::string& path, httplib::Server::Handler handler) {
    posts[path] = handler;
    server.Post(path, std::move(handler));
  }
  void routes();
};

void LiveHttpServer::State::routes() {
  server.Get("/", [this](const httplib::Request&, httplib::Response& res) {
    res.set_content(page, "text/html; charset=utf-8");
  });
  server.Get("/favicon.ico", [](const httplib::Request&, httplib::Response& res) { res.status = 204; });
  server.Get("/state", [this](const httplib::Request&, httplib::Response& res) {
    reply(res, 200, state_json(session.latest(), session.status(), bridge.stats()));
  });
  post("/device", [this](const httplib::Request& req, httplib::Response& res) {
    std::string why;
    const std::optional<Pose> pose = device_pose(req.body, why);
    if (!pose) return reply(res, 400, {{"error", "POST /device: " + why}});
    session.hold_device_pose(*pose);  // a mouse's pose holds until the next
    reply(res, 200, {{"ok", true}});
  });
  post("/reset", [this](const httplib::Request&, httplib::Response& res) {
    session.reset();
    reply(res, 200, {{"ok", true}});
  });
  post("/record/start", [this](const httplib::Request&, httplib::Response& res) {
    const std::lock_guard<std::mutex> lock(record_mutex);
    session.start_recording();
    record_start = std::chrono::steady_clock::now();
    reply(res, 200, {{"recording", true}});
  });
  post("/record/stop", [this](const httplib::Request&, httplib::Response& res) {
    const std::lock_guard<std::mutex> lock(record_mutex);
    try {
      JobResult recorded = session.stop_recording();
      const std::filesystem::path folder = record_base.string() + "-" + std::to_string(++recordings);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - record_start).count();
      const RunReportFiles files = write_job_report(folder, recorded, seconds);
      reply(res, 200, {{"folder", folder.string()}, {"files", files.written}, {"warnings", files.warnings}});
    } catch (const std::exception& e) {
      reply(res, 409, {{"error", e.what()}});
    }
  });
  post("/quit", [this](const httplib::Request&, httplib::Response& res) {
    quit = true;
    reply(res, 200, {{"ok", true}});
  });
  server.set_pre_routing_handler([this](const httplib::Request& req, httplib::Response& res) {
    using Answer = httplib::Server::HandlerResponse;
    if (req.method != "POST" || req.has_header("Content-Length") || req.has_header("Transfer-Encoding"))
      return Answer::Unhandled;
    const auto handler = posts.find(req.path);
    if (handler == posts.end()) return Answer::Unhandled;
    handler->second(req, res);
    return Answer::Handled;
  });
}

LiveHttpServer::LiveHttpServer(LiveSession& session, const BridgeServer& bridge, std::string page, std::uint16_t port,
                               std::filesystem::path record_base)
    : state_(std::make_unique<State>(session, bridge, std::move(page), std::move(record_base))) {
  State& s = *state_;
  // Small replies on a kept-alive connection: without TCP_NODELAY each waits for the
  // client's delayed acknowledgement (tens of ms), slower than the page's 60 Hz.
  s.server.set_tcp_nodelay(true);
  s.routes();
  const int bound = port ? (s.server.bind_to_port("127.0.0.1", port) ? port : -1)
                         : s.server.bind_to_any_port("127.0.0.1");
  if (bound <= 0) throw Error("serve: cannot listen on 127.0.0.1:" + std::to_string(port) + " (in use?)");
  s.port = std::uint16_t(bound);
  s.thread = std::thread([&s] { s.server.listen_after_bind(); });
}

LiveHttpServer::~LiveHttpServer() {
  state_->server.stop();
  state_->thread.join();
}

std::uint16_t LiveHttpServer::port() const { return state_->port; }
bool LiveHttpServer::quit_requested() const { return state_->quit; }

}  // namespace snapfit::cli
