// Progress reports (core/progress.h), in plain (non-terminal) and forced terminal style.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <doctest/doctest.h>
#include <functional>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <tbb/parallel_for.h>
#include <vector>

#include "core/progress.h"
#include "tests/progress_lines.h"

using namespace snapfit;

namespace {

using test::lines_of;
using test::percent_of;

}  // namespace

TEST_CASE("progress: format_duration") {
  CHECK(format_duration(0.0) == "0.0s");
  CHECK(format_duration(0.04) == "0.0s");
  CHECK(format_duration(1.26) == "1.3s");
  CHECK(format_duration(59.5) == "59.5s");
  CHECK(format_duration(59.96) == "1m00s");  // no "60.0s"
  CHECK(format_duration(61.2) == "1m01s");
  CHECK(format_duration(599.0) == "9m59s");
  CHECK(format_duration(3599.6) == "1h00m00s");
  CHECK(format_duration(3723.0) == "1h02m03s");
  CHECK(format_duration(100.0 * 3600 + 5) == "100h00m05s");
  CHECK(format_duration(-1.0) == "?");
  CHECK(format_duration(std::numeric_limits<double>::infinity()) == "?");
  CHECK(format_duration(std::nan("")) == "?");
}

TEST_CASE("progress: line layout and time-left estimate") {
  // 25% in 10 s: 30 s left at that rate.
  CHECK(progress_line("fields", 25, 100, 10.0, false, false) == "fields: 25% (25/100), 10.0s elapsed, ~30.0s left");
  // Under 2% and under 1 s: no estimate yet; past either, there is one.
  CHECK(progress_line("fields", 1, 100, 0.5, false, false) == "fields: 1% (1/100), 0.5s elapsed");
  CHECK(progress_line("fields", 2, 100, 0.5, false, false) == "fields: 2% (2/100), 0.5s elapsed, ~24.5s left");
  CHECK(progress_line("fields", 1, 1000, 1.0, false, false) == "fields: 0% (1/1000), 1.0s elapsed, ~16m39s left");
  CHECK(progress_line("fields", 0, 100, 5.0, false, false) == "fields: 0% (0/100), 5.0s elapsed");
  // Rounded down: 99.99% is not 100%.
  CHECK(progress_line("f", 9999, 10000, 1.0, false, false).find("f: 99%") == 0);
  CHECK(progress_line("f", 100, 100, 3723.0, true, false) == "f: 100% (100/100), done in 1h02m03s");
  CHECK(progress_line("f", 40, 100, 2.0, true, false) == "f: 40% (40/100), stopped after 2.0s");
  CHECK(progress_line("f", 0, 0, 0.0, true, false) == "f: 100% (0/0), done in 0.0s");
  // Terminal layout: a 24-character bar and one decimal.
  CHECK(progress_line("f", 50, 100, 2.0, false, true) ==
        "f [############------------]  50.0%  2.0s elapsed, ~2.0s left");
  CHECK(progress_line("f", 100, 100, 2.0, true, true) == "f [########################] 100.0%  done in 2.0s");
}

TEST_CASE("progress: plain style prints a bounded number of lines, the last says 100%") {
  std::ostringstream out;
  const std::uint64_t total = 100000;
  {
    Progress p("sampling", total, out);
    CHECK_FALSE(p.terminal());  // a string stream is never a terminal
    for (std::uint64_t i = 0; i < total; ++i) p.advance();
    CHECK(p.done() == total);
    p.finish();
    p.finish();   // once only
    p.advance();  // after finish: counted, not printed
  }               // the destructor prints nothing more
  const std::vector<std::string> lines = lines_of(out.str());
  REQUIRE(lines.size() >= 2);
  CHECK(lines.size() <= 12);  // 9 marks of 10% + final (+ 10 s lines on a slow machine)
  CHECK(out.str().find('\r') == std::string::npos);
  std::set<int> percents;
  for (const std::string& line : lines) {
    CAPTURE(line);
    CHECK(percent_of(line, "sampling") >= 0);
    percents.insert(percent_of(line, "sampling"));
  }
  for (int mark = 10; mark <= 90; mark += 10) CHECK(percents.count(mark) == 1);
  CHECK(lines.back().find("sampling: 100% (100000/100000), done in ") == 0);
}

TEST_CASE("progress: concurrent advances from tbb::parallel_for") {
  std::ostringstream out;
  const std::uint64_t total = 200000;
  Progress p("parallel", total, out, ProgressStyle::plain);
  tbb::parallel_for(std::uint64_t(0), total, [&](std::uint64_t) { p.advance(); });
  CHECK(p.done() == total);
  p.finish();
  const std::vector<std::string> lines = lines_of(out.str());
  REQUIRE(!lines.empty());
  CHECK(lines.size() <= 12);
  int last = -1;
  for (const std::string& line : lines) {
    CAPTURE(line);
    const int pct = percent_of(line, "parallel");  // whole lines, never interleaved
    CHECK(pct >= last);
    last = pct;
  }
  CHECK(lines.back().find("parallel: 100% (200000/200000), done in ") == 0);
}

TEST_CASE("progress: advancer, and the destructor reports where it stopped") {
  std::ostringstream out;
  {
    Progress p("tuning", 3000, out);
    const std::function<void(std::uint64_t)> step = p.advancer();
    for (int i = 0; i < 400; ++i) step(3);
    CHECK(p.done() == 1200);
  }
  const std::vector<std::string> lines = lines_of(out.str());
  REQUIRE(!lines.empty());
  CHECK(lines.back().find("tuning: 40% (1200/3000), stopped after ") == 0);
  // 10%, 20%, 30%, 40% marks were passed.
  CHECK(lines.size() == 5);
}

TEST_CASE("progress: terminal style redraws one line at most every 100 ms") {
  std::ostringstream out;
  const auto start = std::chrono::steady_clock::now();
  {
    Progress p("fft", 100000, out, ProgressStyle::terminal);
    CHECK(p.terminal());
    for (int i = 0; i < 100000; ++i) p.advance();
    p.finish();
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const std::string s = out.str();
  const auto redraws = std::count(s.begin(), s.end(), '\r');
  CHECK(redraws >= 2);  // the first advance and the final line
  CHECK(redraws <= 2 + static_cast<long>(ms / 100.0));
  CHECK(std::count(s.begin(), s.end(), '\n') == 1);
  REQUIRE(s.back() == '\n');
  const std::string last = s.substr(s.rfind('\r') + 1);
  CHECK(last.find("fft [########################] 100.0%  done in ") == 0);
}

TEST_CASE("progress: a terminal line shorter than the last one blanks the leftovers") {
  std::ostringstream out;
  {
    Progress p("x", 10, out, ProgressStyle::terminal);
    p.advance(5);  // "... elapsed, ~..s left" is longer than the final "done in" line
    p.advance(5);
  }
  const std::string s = out.str();
  const std::size_t second = s.rfind('\r');
  REQUIRE(second != std::string::npos);
  CHECK(s.size() - second - 2 == s.find('\r', 1) - 1);  // the final line is padded to the first one's width
}

TEST_CASE("progress: reading overrun bars back (tests/progress_lines.h)") {
  CHECK(test::overrun_bars("tuning: 100% (11760/10920), done in 3.1s\n").size() == 1);
  CHECK(test::overrun_bars("a: 104% (52/50), 1.0s elapsed\n").size() == 1);
  CHECK(test::overrun_bars("a: 50% (5/10), 0.1s elapsed\nb: 100% (10/10), done in 0.2s\nnot a bar (3/2)\n").empty());
}
