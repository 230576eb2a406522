// Progress reports for long host work (core/progress.h).
#include "core/progress.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <unistd.h>
#include <utility>

namespace snapfit {
namespace {

constexpr std::int64_t kTerminalPeriodNs = 100'000'000;  // 100 ms
constexpr std::int64_t kPlainPeriodNs = 10'000'000'000;  // 10 s
constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();
constexpr int kBarWidth = 24;

bool is_terminal(const std::ostream& out, ProgressStyle style) {
  if (style != ProgressStyle::automatic) return style == ProgressStyle::terminal;
  if (&out == &std::cerr || &out == &std::clog) return ::isatty(STDERR_FILENO) == 1;
  if (&out == &std::cout) return ::isatty(STDOUT_FILENO) == 1;
  return false;
}

double fraction(std::uint64_t done, std::uint64_t total) {
  if (total == 0) return 1.0;
  return std::min(1.0, static_cast<double>(done) / static_cast<double>(total));
}

// floor(done * parts / total), exact for any counts; parts when done >= total.
std::uint64_t parts_done(std::uint64_t done, std::uint64_t total, std::uint64_t parts) {
  if (done >= total) return parts;
  return static_cast<std::uint64_t>(static_cast<unsigned __int128>(done) * parts / total);
}

// The first count at or past the next whole 10% of `total`; kNever past 90%.
std::uint64_t next_tenth(std::uint64_t done, std::uint64_t total) {
  const std::uint64_t k = parts_done(done, total, 10) + 1;
  if (k >= 10) return kNever;
  return static_cast<std::uint64_t>((static_cast<unsigned __int128>(total) * k + 9) / 10);  // ceil
}

}  // namespace

std::string format_duration(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0 || seconds > 9e18) return "?";
  char buf[48];
  if (std::round(seconds * 10.0) < 600.0) {
    std::snprintf(buf, sizeof buf, "%.1fs", std::round(seconds * 10.0) / 10.0);
    return buf;
  }
  const long long s = std::llround(seconds);
  if (s < 3600)
    std::snprintf(buf, sizeof buf, "%lldm%02llds", s / 60, s % 60);
  else
    std::snprintf(buf, sizeof buf, "%lldh%02lldm%02llds", s / 3600, s / 60 % 60, s % 60);
  return buf;
}

std::string progress_line(const std::string& label, std::uint64_t done, std::uint64_t total, double elapsed_s,
                          bool final, bool terminal, const std::string& rate_unit) {
  const double f = fraction(done, total);
  const bool complete = done >= total;
  char pct[16];
  if (terminal)
    std::snprintf(pct, sizeof pct, "%5.1f%%", static_cast<double>(parts_done(done, total, 1000)) / 10.0);
  else
    std::snprintf(pct, sizeof pct, "%d%%", static_cast<int>(parts_done(done, total, 100)));
  std::string line = label;
  if (terminal) {
    const int filled = static_cast<int>(parts_done(done, total, kBarWidth));
    line += " [" + std::string(filled, '#') + std::string(kBarWidth - filled, '-') + "] " + pct + "  ";
  } else {
    line += std::string(": ") + pct + " (" + std::to_string(done) + "/" + std::to_string(total) + "), ";
  }
  if (!rate_unit.empty() && elapsed_s > 0) {
    char rate[64];
    std::snprintf(rate, sizeof rate, "%.3g %s/s, ", static_cast<double>(done) / elapsed_s, rate_unit.c_str());
    line += rate;
  }
  if (final) return line + (complete ? "done in " : "stopped after ") + format_duration(elapsed_s);
  line += format_duration(elapsed_s) + " elapsed";
  if (done > 0 && !complete && (f >= 0.02 || elapsed_s >= 1.0))
    line +=
        ", ~" + format_duration(elapsed_s * static_cast<double>(total - done) / static_cast<double>(done)) + " left";
  return line;
}

Progress::Progress(std::string label, std::uint64_t total, std::ostream& out, ProgressStyle style)
    : label_(std::move(label)),
      total_(total),
      out_(out),
      terminal_(is_terminal(out, style)),
      start_(Clock::now()),
      next_draw_ns_(terminal_ ? 0 : kPlainPeriodNs),
      next_count_(terminal_ ? kNever : next_tenth(0, total)) {}

Progress::~Progress() {
  try {
    finish();
  } catch (...) {  // a failing stream must not end the program
  }
}

void Progress::advance(std::uint64_t n) {
  const std::uint64_t d = done_.fetch_add(n, std::memory_order_relaxed) + n;
  if (finished_.load(std::memory_order_relaxed)) return;
  const std::int64_t t = std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_).count();
  auto due = [&] {
    return t >= next_draw_ns_.load(std::memory_order_relaxed) || d >= next_count_.load(std::memory_order_relaxed);
  };
  if (!due()) return;
  // Whoever holds the lock is drawing already; the next advance catches up.
  std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
  if (!lock.owns_lock() || finished_.load() || !due()) return;
  const std::uint64_t now_done = done_.load();
  next_draw_ns_.store(t + (terminal_ ? kTerminalPeriodNs : kPlainPeriodNs));
  if (!terminal_) next_count_.store(next_tenth(now_done, total_.load()));
  draw(false);
}

void Progress::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_.exchange(true)) return;
  draw(true);
}

void Progress::extend_to(std::uint64_t total) {
  std::uint64_t now = total_.load();
  while (total > now)
    if (total_.compare_exchange_weak(now, total)) {
      if (!terminal_) next_count_.store(next_tenth(done_.load(), total));
      return;
    }
}

std::function<void(std::uint64_t)> Progress::advancer() {
  return [this](std::uint64_t n) { advance(n); };
}

void Progress::draw(bool final) {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_).count();
  const std::string line = progress_line(label_, done_.load(), total_.load(), elapsed, final, terminal_, rate_unit_);
  if (terminal_) {
    // Blank what is left of a longer previous line.
    const std::string pad(last_width_ > line.size() ? last_width_ - line.size() : 0, ' ');
    out_ << '\r' << line << pad;
    if (final) out_ << '\n';
    last_width_ = line.size();
  } else {
    out_ << line << '\n';
  }
  out_.flush();
}

std::function<void(const std::string&, std::uint64_t, std::uint64_t)> pass_progress_bars(std::ostream& out) {
  struct State {
    std::string pass;
    std::unique_ptr<Progress> bar;
    std::uint64_t reported = 0;
  };
  auto state = std::make_shared<State>();
  return [state, &out](const std::string& pass, std::uint64_t done, std::uint64_t total) {
    // A new pass, or the same pass name starting over (one callback reused for several
    // computations, e.g. both parts of a scene): a new bar.
    if (!state->bar || pass != state->pass || done < state->reported || state->bar->done() >= total) {
      if (state->bar) state->bar->finish();
      state->pass = pass;
      state->bar = std::make_unique<Progress>(pass, total, out);
      state->reported = 0;
    }
    state->bar->extend_to(total);  // a pass that found more work than it first said
    state->bar->advance(done - state->reported);
    state->reported = done;
    if (done >= total) state->bar->finish();
  };
}

}  // namespace snapfit
