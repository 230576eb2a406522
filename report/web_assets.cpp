#include "report/web_assets.h"

#include "snapfit/error.h"

namespace snapfit {

bool web_pages_available() { return !embedded_web_assets().empty(); }

std::string_view web_asset(const std::string& name) {
  const auto& assets = embedded_web_assets();
  if (assets.empty())
    throw Error("this snapfit was built without the web report (SNAPFIT_WEB_REPORT=OFF, see docs/haptics.md): no " +
                name);
  std::string known;
  for (const WebAsset& a : assets) {
    if (a.name == name) return a.text;
    known += (known.empty() ? "" : ", ") + std::string(a.name);
  }
  throw Error("no embedded web asset '" + name + "' (known: " + known + ")");
}

}  // namespace snapfit
