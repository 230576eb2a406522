#include "report/html_page.h"

#include "report/web_assets.h"
#include "snapfit/export.h"

namespace snapfit {
namespace {

// JSON that cannot end its <script> element: '<' occurs only inside JSON strings, where
// \u003c reads back as '<'. ASCII only; invalid UTF-8 in names becomes U+FFFD.
std::string inline_json(const nlohmann::json& data) {
  const std::string text = data.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

}  // namespace

std::string html_page(const std::string& page, const std::string& title, const nlohmann::json& data) {
  const std::string_view script = web_asset(page + ".js"), style = web_asset(page + ".css");
  std::string html;
  html.reserve(script.size() + style.size() + 4096);
  html += "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  html += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  html += "<meta name=\"generator\" content=\"snapfit\">\n<title>" + escape_markup(title) + "</title>\n<style>\n";
  html += style;
  html += "\n</style>\n</head>\n<body>\n<div id=\"app\"></div>\n";
  html += "<script id=\"snapfit-data\" type=\"application/json\">" + inline_json(data) + "</script>\n<script>\n";
  html += script;
  html += "\n</script>\n</body>\n</html>\n";
  return html;
}

void write_html_page(const std::string& path, const std::string& page, const std::string& title,
                     const nlohmann::json& data) {
  write_text_file(path, html_page(page, title, data));
}

}  // namespace snapfit
