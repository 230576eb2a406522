// Charts as data for the browser (report/chart_spec.h) and self-contained pages
// (report/html_page.h, report/page_encoding.h).
#include <cmath>
#include <cstring>
#include <doctest/doctest.h>
#include <string>
#include <vector>

#include "report/chart_spec.h"
#include "report/html_page.h"
#include "report/page_encoding.h"
#include "report/web_assets.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("page encoding: base64 matches RFC 4648 and float32 round-trips") {
  // RFC 4648 section 10 test vectors.
  const std::pair<const char*, const char*> vectors[] = {{"", ""},
                                                         {"f", "Zg=="},
                                                         {"fo", "Zm8="},
                                                         {"foo", "Zm9v"},
                                                         {"foob", "Zm9vYg=="},
                                                         {"fooba", "Zm9vYmE="},
                                                         {"foobar", "Zm9vYmFy"}};
  for (const auto& [in, out] : vectors)
    CHECK(base64_encode(reinterpret_cast<const unsigned char*>(in), std::strlen(in)) == out);
  std::vector<unsigned char> all(256);
  for (int i = 0; i < 256; ++i) all[i] = static_cast<unsigned char>(i);
  CHECK(test::decode_base64(base64_encode(all.data(), all.size())) == all);

  const std::vector<double> values = {0.0, -1.5, 1e-3, 3.4e38, std::nan(""), HUGE_VAL, 0.1};
  const std::vector<unsigned char> bytes = test::decode_base64(float32_base64(values));
  REQUIRE(bytes.size() == 4 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    float f;
    std::memcpy(&f, bytes.data() + 4 * i, 4);
    if (std::isnan(values[i]))
      CHECK(std::isnan(f));
    else
      CHECK(f == static_cast<float>(values[i]));
  }
}

TEST_CASE("chart spec: series, shared x, markers, reference lines and limits as JSON") {
  Chart c;
  c.title = "t";
  c.x_label = "m'";
  c.y_label = "ms";
  c.log_x = c.log_y = true;
  c.series.push_back(Series{"p50", {1, 2, 4}, {0.1, std::nan(""), 0.4}, Series::Style::line_points, ""});
  c.series.push_back(Series{"p99", {1, 2, 4}, {0.2, 0.3, 0.5}, Series::Style::bars, "#00ff00"});
  c.markers.push_back(Marker{2, 0.3, "chosen"});
  c.markers.push_back(Marker{std::nan(""), 1, "dropped"});
  c.hlines.push_back(HLine{1, "budget"});
  nlohmann::json j = chart_json(c);
  CHECK(j["title"] == "t");
  CHECK(j["log_x"] == true);
  CHECK(j["x"] == nlohmann::json({1.0, 2.0, 4.0}));  // shared: written once
  REQUIRE(j["series"].size() == 2);
  CHECK_FALSE(j["series"][0].contains("x"));
  CHECK(j["series"][0]["y"] == nlohmann::json({0.1, nullptr, 0.4}));
  CHECK(j["series"][0]["style"] == "line_points");
  CHECK(j["series"][1]["style"] == "bars");
  CHECK(j["series"][1]["color"] == "#00ff00");
  CHECK(j["markers"] == nlohmann::json::parse(R"([{"x":2.0,"y":0.3,"label":"chosen"}])"));
  CHECK(j["hlines"] == nlohmann::json::parse(R"([{"y":1.0,"label":"budget"}])"));
  CHECK(j["x_min"].is_null());

  // Different x: each series keeps its own; long arrays go as float32 base64.
  c.series[1].x = {1, 3, 5};
  std::vector<double> many(1000);
  for (std::size_t i = 0; i < many.size(); ++i) many[i] = 0.5 * double(i);
  c.series.push_back(Series{"long", many, many, Series::Style::line, ""});
  j = chart_json(c);
  CHECK_FALSE(j.contains("x"));
  CHECK(j["series"][1]["x"] == nlohmann::json({1.0, 3.0, 5.0}));
  REQUIRE(j["series"][2]["y"].is_string());
  const std::vector<unsigned char> bytes = test::decode_base64(j["series"][2]["y"].get<std::string>());
  REQUIRE(bytes.size() == 4000);
  float f;
  std::memcpy(&f, bytes.data() + 4 * 999, 4);
  CHECK(f == 499.5f);

  // Errors name the chart and the problem.
  Chart bad;
  bad.title = "bad";
  bad.series.push_back(Series{"short", {1, 2, 3}, {1, 2}, Series::Style::line, ""});
  CHECK(test::error_of([&] { chart_json(bad); }) == "chart 'bad': series 'short' has 3 x values and 2 y values");
  bad.series = {Series{"c", {1}, {1}, Series::Style::line, "red"}};
  CHECK(test::error_of([&] { chart_json(bad); }).find("is not #rrggbb") != std::string::npos);
  bad.series.clear();
  bad.x_min = bad.x_max = 5;
  CHECK(test::error_of([&] { chart_json(bad); }).find("not increasing") != std::string::npos);
  bad.x_min = 0;
  bad.x_max = 10;
  bad.log_x = true;
  CHECK(test::error_of([&] { chart_json(bad); }).find("positive") != std::string::npos);
}

TEST_CASE("chart spec: histogram_chart bins finite values into bars") {
  std::vector<double> values;
  for (int i = 0; i < 100; ++i) values.push_back(i);
  values.push_back(std::nan(""));
  Chart c = histogram_chart("h", "value", values, 10, false);
  REQUIRE(c.series.size() == 1);
  const Series& s = c.series[0];
  CHECK(s.style == Series::Style::bars);
  CHECK(s.label == "100 values (1 not finite)");
  CHECK(c.y_label == "count");
  REQUIRE(s.x.size() == 10);
  CHECK(s.x[0] == doctest::Approx(4.95));
  CHECK(s.x[9] == doctest::Approx(94.05));
  for (double y : s.y) CHECK(y == 10);
  // Brute force: every value is counted in the bin whose range holds it.
  std::vector<double> skewed = {0.0, 0.01, 0.2, 0.25, 0.26, 0.9, 1.0, 1.0, 1.0};
  const Chart h = histogram_chart("", "", skewed, 4);
  const std::vector<double> want = {3, 2, 0, 4};  // [0, .25) [.25, .5) [.5, .75) [.75, 1]
  CHECK(h.series[0].y == want);
  CHECK(histogram_chart("", "", {}, 5).series[0].x.empty());
  CHECK(histogram_chart("", "", {3, 3, 3}, 5).series[0].y[2] == 3);
  CHECK(test::error_of([] { histogram_chart("h", "", {1}, 0); }).find("bins") != std::string::npos);
}

TEST_CASE("html page: self-contained, its data block cannot end early") {
  if (!web_pages_available()) {
    CHECK(test::error_of([] { html_page("chart_page", "t", {}); }).find("SNAPFIT_WEB_REPORT=OFF") != std::string::npos);
    return;
  }
  const nlohmann::json data = {{"kind", "charts"}, {"title", "a </script><script>alert(1)</script> & <b>"}};
  const std::string html = html_page("chart_page", "a </script> & <b>", data);
  CHECK(html.rfind("<!doctype html>", 0) == 0);
  CHECK(html.find("<title>a &lt;/script&gt; &amp; &lt;b&gt;</title>") != std::string::npos);
  // The data block: one element, '<' written as \u003c, and it reads back as the data.
  const std::string open = "<script id=\"snapfit-data\" type=\"application/json\">";
  const std::size_t at = html.find(open);
  REQUIRE(at != std::string::npos);
  const std::size_t end = html.find("</script>", at);
  const std::string block = html.substr(at + open.size(), end - at - open.size());
  CHECK(block.find('<') == std::string::npos);
  CHECK(nlohmann::json::parse(block) == data);
  // Everything inline: no script, style or image is fetched.
  for (const char* fetch : {"<script src", "<link", "@import", "<img src=\"http", "url(http"})
    CHECK(html.find(fetch) == std::string::npos);
  CHECK(html.find(std::string(web_asset("chart_page.js"))) != std::string::npos);
  CHECK(test::error_of([] { web_asset("nothing.js"); }).find("known: ") != std::string::npos);

  // Written atomically where asked; a missing folder is named.
  test::TempDir dir;
  write_chart_page(dir.file("c.html"), "c", {"note"}, {histogram_chart("h", "v", {1, 2, 2, 3}, 3)});
  CHECK(test::read_bytes(dir.file("c.html")).size() > web_asset("chart_page.js").size());
  CHECK(test::error_of([&] { write_chart_page(dir.file("no/c.html"), "c", {}, {}); }).find("no/c.html") !=
        std::string::npos);
}
