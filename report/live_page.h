#pragma once
// The page of `snapfit serve`: the report's 3D view, live (report/web/src/live_page.js),
// with both parts of the session's record and where the session listens.
#include <cstdint>
#include <string>

#include "snapfit/job.h"

namespace snapfit {

struct LivePageInfo {
  std::uint16_t bridge_port = 0;  // the device bridge's UDP port, shown on the page
  double state_hz = 60;           // how often the page asks for the loop's latest frame
};

// The page's HTML, self-contained but for its requests to the session (GET /state, POST
// /device, /reset, /record/start, /record/stop). Throws snapfit::Error when this build
// has no web report.
std::string live_page_html(const JobResult& prepared, const LivePageInfo& info);

}  // namespace snapfit
