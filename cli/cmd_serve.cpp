// `snapfit serve SCENE`: a live session (snapfit::LiveSession, snapfit/live.h) with a page
// on 127.0.0.1 where the mouse is the haptic device (cli/live_server.h), and the device
// bridge (snapfit/bridge.h) where a device program in any language can be instead. Runs
// until Ctrl-C or POST /quit, then says how the session ended.
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <thread>

#include "cli/cli_terms.h"
#include "cli/commands.h"
#include "cli/live_server.h"
#include "cli/parse_options.h"
#include "report/live_page.h"
#include "snapfit/bridge.h"
#include "snapfit/live.h"

namespace snapfit::cli {
namespace {

struct ServeOptions {
  std::string scene;
  std::uint16_t port = 8765;
  std::optional<std::uint16_t> bridge_port;  // default: port + 1 (0 with --port 0)
  std::string device;
  std::optional<std::size_t> modes;
  std::string strategy = "auto";
  std::string loop_wait = "spin";
  std::string out;
  double late_ms = 5, fade_ms = 100;
};

volatile std::sig_atomic_t interrupted = 0;
extern "C" void on_signal(int) { interrupted = 1; }

void print_end(const Scene& scene, const LiveStatus& s, const BridgeStats& b) {
  std::cout << "session ended: " << s.frames << " frames in " << s.elapsed_s << " s, " << s.misses << " misses, "
            << s.sanitised << " non-finite wrenches sent as zero; bridge: " << b.states << " states, " << b.malformed
            << " malformed, " << b.refused << " refused\n"
            << "final pose error " << s.position_error << " " << scene.units << ", " << s.angle_error_deg
            << " deg, surface " << s.surface_deviation << " " << scene.units << " off: "
            << (!s.evaluated  ? "not evaluated (the scene has no assembled pose)"
                : s.assembled ? "ASSEMBLED"
                              : "NOT assembled")
            << "\n";
}

void run_serve(const ServeOptions& opt) {
  std::cout << "[1/7] reading scene " << opt.scene << "\n";
  const Scene scene = load_scene(opt.scene);
  const std::filesystem::path out =
      opt.out.empty() ? std::filesystem::path("results") / (std::filesystem::path(opt.scene).stem().string() + "-live")
                      : std::filesystem::path(opt.out);
  JobRequest request;
  request.device = opt.device;
  request.modes = opt.modes.value_or(0);
  request.strategy = opt.strategy;
  request.loop_wait = parse_loop_wait(opt.loop_wait);
  request.progress = true;
  request.say = [](const std::string& text) { std::cout << in_cli_terms(text) << std::flush; };
  request.note = [](const std::string& text) { std::cerr << "snapfit: " << in_cli_terms(text) << "\n"; };

  // The loop sends each frame to the bridge, the bridge hands each state to the session:
  // the session's loop stops first, then the bridge, then the session goes.
  std::unique_ptr<BridgeServer> bridge;
  LiveOptions live;
  live.late_s = opt.late_ms / 1e3;
  live.fade_s = opt.fade_ms / 1e3;
  live.on_frame = [&bridge](const LiveFrame& frame) { bridge->send_frame(frame); };
  LiveSession session(scene, request, live);
  bridge = std::make_unique<BridgeServer>(
      opt.bridge_port.value_or(opt.port ? std::uint16_t(opt.port + 1) : 0),
      [&session](const BodyState& state, std::uint32_t sequence) { session.set_device_state(state, sequence); });
  struct StopInOrder {  // on every way out of this function
    LiveSession& session;
    std::unique_ptr<BridgeServer>& bridge;
    ~StopInOrder() {
      try {
        session.stop();
      } catch (...) {  // reported by the explicit stop() below when there is one
      }
      bridge.reset();
    }
  } stop_in_order{session, bridge};
  LiveHttpServer http(session, *bridge, live_page_html(session.prepared(), LivePageInfo{bridge->port()}), opt.port,
                      out);
  session.start();
  std::cout << "[7/7] live: the page at http://127.0.0.1:" << http.port()
            << "/ , the device bridge at UDP 127.0.0.1:" << bridge->port()
            << " (docs/haptics.md); Ctrl-C ends the session" << std::endl;
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  while (!interrupted && !http.quit_requested()) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const LiveStatus end = session.stop();
  print_end(scene, end, bridge->stats());
}

}  // namespace

void add_serve_command(CLI::App& app) {
  auto opt = std::make_shared<ServeOptions>();
  CLI::App* cmd = app.add_subcommand(
      "serve", "A live session: the loop at 1 kHz, a page where the mouse is the device, and the device bridge");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option("--port", opt->port, "The page's port on 127.0.0.1 (default 8765; 0: a free one)");
  cmd->add_option("--bridge-port", opt->bridge_port,
                  "The device bridge's UDP port on 127.0.0.1 (default: --port + 1; a free one with --port 0)");
  cmd->add_option("--device", opt->device, "OpenCL device (see `snapfit devices`)");
  cmd->add_option("--modes", opt->modes, "m': a fixed number of Fourier modes instead of the tuned one")
      ->check(positive_number());
  cmd->add_option("--strategy", opt->strategy,
                  "Query strategy: auto (default), tricubic, trilinear, exact-product or near-far")
      ->check(CLI::IsMember(strategy_choices()));
  cmd->add_option("--loop-wait", opt->loop_wait, "How the loop waits for its tick: spin (default) or sleep")
      ->check(CLI::IsMember({"spin", "sleep"}));
  cmd->add_option("--late-ms", opt->late_ms, "A device state older than this is late: held, the wrench fading (5)")
      ->check(positive_number());
  cmd->add_option("--fade-ms", opt->fade_ms, "The wrench fades to zero over this long after --late-ms (100)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", opt->out, "Recordings go to OUT-1, OUT-2, ... (default: results/<scene>-live)");
  cmd->callback([opt] { run_serve(*opt); });
}

}  // namespace snapfit::cli
