#pragma once
// Progress reports for long host work (field sampling, FFT batches, tuning sweeps).
//
// On a terminal one line is redrawn in place with '\r', at most every 100 ms:
//   "spectra [##########--------------]  41.7%  12.3s elapsed, ~17.2s left"
// Elsewhere (CI logs, pipes, files) a plain line is printed at each 10% mark or every
// 10 s, whichever comes first, so logs stay short:
//   "spectra: 40% (4000/10000), 12.3s elapsed, ~18.5s left"
// finish() prints the final line with the total time ("..., done in 30.1s"; "stopped
// after" when fewer than `total` steps were counted). The time left is the rate so far
// extrapolated, shown once 2% is done or 1 s has passed.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <iostream>
#include <mutex>
#include <string>

#include "snapfit/progress.h"

namespace snapfit {

// Seconds of steady time since `start`.
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Durations for people: "0.0s" to "59.9s" (tenths), then "1m05s", then "1h02m03s"
// (whole seconds, rounded). "?" for a negative or non-finite value.
std::string format_duration(double seconds);

// One report line without '\r' or '\n'. `terminal` picks the bar layout, `final` the
// closing wording; percentages are rounded down so 100% means all steps are done. A
// non-empty `rate_unit` adds the steps per second so far ("12.5 rotations/s").
std::string progress_line(const std::string& label, std::uint64_t done, std::uint64_t total, double elapsed_s,
                          bool final, bool terminal, const std::string& rate_unit = "");

enum class ProgressStyle {
  automatic,  // terminal when `out` is std::cerr/std::clog (std::cout) and fd 2 (1) is a tty
  terminal,
  plain,
};

class Progress {
 public:
  Progress(std::string label, std::uint64_t total, std::ostream& out = std::cerr,
           ProgressStyle style = ProgressStyle::automatic);
  // Show the steps per second, named `unit` per second (progress_line's rate_unit).
  void show_rate(const std::string& unit) { rate_unit_ = unit; }
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;
  // Calls finish() if it was not called (so an aborted run says where it stopped).
  ~Progress();

  // Counts n more steps and redraws when due. Thread-safe; cheap when no redraw is due.
  void advance(std::uint64_t n = 1);
  // Prints the final line once; later calls and advances print nothing.
  void finish();
  // advance() as a callback for code that does not know about Progress. The Progress
  // must outlive it.
  std::function<void(std::uint64_t)> advancer();

  // The work turned out larger than first said (a tuning level measured twice): the
  // total becomes `total` when that is more, so the bar never runs past 100 %.
  void extend_to(std::uint64_t total);

  std::uint64_t done() const { return done_.load(); }
  std::uint64_t total() const { return total_.load(); }
  bool terminal() const { return terminal_; }

 private:
  using Clock = std::chrono::steady_clock;
  void draw(bool final);  // with mutex_ held

  const std::string label_;
  std::atomic<std::uint64_t> total_;
  std::ostream& out_;
  const bool terminal_;
  const Clock::time_point start_;
  std::atomic<std::uint64_t> done_{0};
  std::atomic<std::int64_t> next_draw_ns_{0};  // since start_: the next timed redraw
  std::atomic<std::uint64_t> next_count_;      // plain style: the next 10% mark
  std::atomic<bool> finished_{false};
  std::mutex mutex_;            // guards out_ and last_width_
  std::size_t last_width_ = 0;  // terminal: the last line's length, to blank leftovers
  std::string rate_unit_;       // empty: no rate shown
};

}  // namespace snapfit
