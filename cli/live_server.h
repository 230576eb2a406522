#pragma once
// The HTTP side of `snapfit serve` on 127.0.0.1 (cpp-httplib): the live page, the loop's
// latest frame as JSON, the mouse's device pose, reset, recording and quit.
//   GET  /              the page (report/live_page.h)
//   GET  /state         {frame, status, bridge}: the loop's latest frame and the totals
//   POST /device        {position [x,y,z], quaternion [w,x,y,z]}: the mouse's device pose, held until the next
//   POST /reset         part 2 and the device back to the scene's initial pose
//   POST /record/start  keep the frames from now on
//   POST /record/stop   write them as a report folder (loop.csv, report.html, ...): {folder, files}
//   POST /quit          end the session
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include "snapfit/bridge.h"
#include "snapfit/live.h"

namespace snapfit::cli {

class LiveHttpServer {
 public:
  // Binds 127.0.0.1:`port` (0: a free port) and serves on its own thread. Recordings go
  // to `record_base`-1, -2, ... Throws snapfit::Error naming the port when it cannot bind.
  LiveHttpServer(LiveSession& session, const BridgeServer& bridge, std::string page, std::uint16_t port,
                 std::filesystem::path record_base);
  ~LiveHttpServer();
  LiveHttpServer(const LiveHttpServer&) = delete;
  LiveHttpServer& operator=(const LiveHttpServer&) = delete;

  std::uint16_t port() const;
  bool quit_requested() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace snapfit::cli
