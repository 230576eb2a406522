#pragma once
// Self-contained HTML pages: the page's bundled script and style sheet
// (report/web_assets.h) and its data as one JSON block, all inline, so the file opens
// from disk with no network. report/web/src reads the block (page_data.js).
#include <nlohmann/json.hpp>
#include <string>

namespace snapfit {

// The page `page` ("run_report" or "chart_page") titled `title` with `data` inlined.
// Throws snapfit::Error when this build has no web report (report/web_assets.h).
std::string html_page(const std::string& page, const std::string& title, const nlohmann::json& data);

// html_page written atomically to `path`.
void write_html_page(const std::string& path, const std::string& page, const std::string& title,
                     const nlohmann::json& data);

}  // namespace snapfit
