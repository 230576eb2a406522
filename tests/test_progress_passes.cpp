// One progress bar per named pass (core/progress.h pass_progress_bars), in plain
// (non-terminal) style into a string stream.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <doctest/doctest.h>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "core/progress.h"
#include "tests/progress_lines.h"

using namespace snapfit;

namespace {

using test::lines_of;
using test::percent_of;

// Reports a pass the way compute_descriptors does: after every chunk, (name, done, total).
void run_pass(const std::function<void(const std::string&, std::uint64_t, std::uint64_t)>& report,
              const std::string& name, std::uint64_t total, std::uint64_t chunk) {
  for (std::uint64_t first = 0; first < total; first += chunk) report(name, std::min(total, first + chunk), total);
}

}  // namespace

TEST_CASE("progress passes: three passes give three finished bars at 100%, in order") {
  std::ostringstream out;
  const std::vector<std::string> passes = {"distance", "winding number", "skeletal density"};
  const std::uint64_t total = 100000;
  {
    const auto report = pass_progress_bars(out);
    for (const std::string& pass : passes) run_pass(report, pass, total, 16384);
  }
  const std::vector<std::string> lines = lines_of(out.str());
  CAPTURE(out.str());
  REQUIRE(!lines.empty());
  CHECK(out.str().find('\r') == std::string::npos);  // a string stream is not a terminal

  // Every line belongs to a pass, the passes appear in order and never interleave.
  std::size_t at = 0;
  std::vector<std::string> finals;
  for (std::size_t p = 0; p < passes.size(); ++p) {
    const std::string& name = passes[p];
    CAPTURE(name);
    std::size_t count = 0;
    int last_percent = -1;
    while (at < lines.size() && test::starts_with(lines[at], name + ": ")) {
      const int pct = percent_of(lines[at], name);
      CHECK(pct >= last_percent);  // never goes back
      last_percent = pct;
      ++count;
      ++at;
    }
    REQUIRE(count >= 1);
    CHECK(count <= 12);  // plain style: about one line per 10%, plus the final one
    const std::string& last = lines[at - 1];
    CHECK(last_percent == 100);
    CHECK(last.find("(100000/100000)") != std::string::npos);
    CHECK(last.find("done in") != std::string::npos);
    finals.push_back(last);
  }
  CHECK(at == lines.size());  // nothing after the third bar, nothing unaccounted for
  CHECK(finals.size() == 3);
  // Exactly one final line per pass.
  std::size_t done_lines = 0;
  for (const auto& line : lines) done_lines += line.find("done in") != std::string::npos;
  CHECK(done_lines == 3);
}

TEST_CASE("progress passes: different totals, single-chunk passes, and a pass cut short") {
  std::ostringstream out;
  {
    const auto report = pass_progress_bars(out);
    run_pass(report, "a", 7, 7);     // one report reaching the total
    run_pass(report, "b", 1000, 3);  // many small steps
    report("c", 40, 100);            // stops at 40%...
    run_pass(report, "d", 50, 10);   // ...when the next pass starts
  }
  const std::vector<std::string> lines = lines_of(out.str());
  CAPTURE(out.str());
  std::vector<std::string> finals;
  for (const auto& line : lines)
    if (line.find("done in") != std::string::npos || line.find("stopped after") != std::string::npos)
      finals.push_back(line);
  REQUIRE(finals.size() == 4);
  CHECK(test::starts_with(finals[0], "a: 100% (7/7), done in"));
  CHECK(test::starts_with(finals[1], "b: 100% (1000/1000), done in"));
  CHECK(test::starts_with(finals[2], "c: 40% (40/100), stopped after"));
  CHECK(test::starts_with(finals[3], "d: 100% (50/50), done in"));
  // Lines of each pass come before the next pass's.
  std::string order;
  for (const auto& line : lines)
    if (order.empty() || order.back() != line[0]) order += line[0];
  CHECK(order == "abcd");
}

TEST_CASE("progress passes: a pass whose total grows as it goes never runs past 100 %") {
  // As the m' sweep reports: each level once, and again when it missed the target, the
  // total growing by a level each time.
  std::ostringstream out;
  {
    const auto report = pass_progress_bars(out);
    std::uint64_t done = 0, total = 5 * 100;
    report("tuning", 0, total);
    for (int level = 0; level < 5; ++level) {
      done += 100;
      if (level >= 3) {
        total += 100;
        report("tuning", done, total);
        done += 100;
      }
      report("tuning", done, total);
    }
    report("tuning", total, total);
  }
  const std::vector<std::string> lines = lines_of(out.str());
  CAPTURE(out.str());
  REQUIRE(!lines.empty());
  for (const std::string& line : lines) {
    CHECK(percent_of(line, "tuning") <= 100);
    const std::size_t open = line.find('('), slash = line.find('/'), close = line.find(')');
    REQUIRE(open != std::string::npos);
    const std::uint64_t shown_done = std::strtoull(line.c_str() + open + 1, nullptr, 10),
                        shown_total = std::strtoull(line.c_str() + slash + 1, nullptr, 10);
    CHECK(close > slash);
    CHECK(shown_done <= shown_total);
  }
  CHECK(test::starts_with(lines.back(), "tuning: 100% (700/700), done in"));
}
