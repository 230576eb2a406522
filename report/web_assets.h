#pragma once
// The bundled browser code of snapfit's pages (report/web, bundled by esbuild and
// embedded at build time by cmake/EmbedWebAssets.cmake): for each page a script
// "<page>.js" and a style sheet "<page>.css". A build with -DSNAPFIT_WEB_REPORT=OFF
// embeds none.
#include <string>
#include <string_view>
#include <vector>

namespace snapfit {

struct WebAsset {
  const char* name;  // file name, e.g. "run_report.js"
  std::string_view text;
};

// Every embedded asset, in file-name order (empty without the web report).
const std::vector<WebAsset>& embedded_web_assets();

// Whether this build embeds the pages' code (SNAPFIT_WEB_REPORT).
bool web_pages_available();

// The asset named `name`; throws snapfit::Error saying the build has no web report, or
// listing the known names.
std::string_view web_asset(const std::string& name);

}  // namespace snapfit
