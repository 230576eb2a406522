// How often this machine takes the CPU away from a thread that never sleeps: spins on one
// thread reading the steady clock for SECONDS and reports every gap between two readings
// over 0.2 ms (time the thread did not run: the host descheduling a virtual CPU, an
// interrupt, or, with `fifo`, the kernel's real-time throttling). Run one copy alone, then
// two at once (one per CPU) to see what the haptic loop gets while another process is busy
// (docs/haptics.md "Waiting for the tick"). Not built by CMake:
//
//   g++ -O2 -o /tmp/vcpu_gaps perf/vcpu_gaps.cpp && /tmp/vcpu_gaps 30 [fifo]
#include <sched.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

int main(int argc, char** argv) {
  const double seconds = argc > 1 ? std::atof(argv[1]) : 30;
  const bool want_fifo = argc > 2 && std::strcmp(argv[2], "fifo") == 0;
  sched_param param{};
  param.sched_priority = 10;
  const bool fifo = want_fifo && sched_setscheduler(0, SCHED_FIFO, &param) == 0;
  if (want_fifo && !fifo) std::fprintf(stderr, "vcpu_gaps: SCHED_FIFO refused, running SCHED_OTHER\n");
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  auto last = start;
  std::vector<double> gaps;
  for (;;) {
    const auto now = Clock::now();
    const double gap_ms = std::chrono::duration<double, std::milli>(now - last).count();
    if (gap_ms > 0.2) gaps.push_back(gap_ms);
    last = now;
    if (std::chrono::duration<double>(now - start).count() > seconds) break;
  }
  int over_half = 0, over_1 = 0, over_2 = 0;
  double longest = 0, total = 0;
  for (const double g : gaps) {
    over_half += g > 0.5, over_1 += g > 1, over_2 += g > 2;
    longest = g > longest ? g : longest;
    total += g;
  }
  std::printf("%s, %.0f s: %zu gaps over 0.2 ms (over 0.5 ms: %d, over 1 ms: %d, over 2 ms: %d), longest %.2f ms, "
              "%.1f ms in all\n",
              fifo ? "SCHED_FIFO 10" : "SCHED_OTHER", seconds, gaps.size(), over_half, over_1, over_2, longest, total);
}
