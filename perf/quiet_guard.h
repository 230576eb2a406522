#pragma once
// Measuring on a shared machine: a measurement is repeated while other processes kept
// more than `threshold` cores busy during it, after waiting `wait_s`, up to `max_retries`
// times per point and `budget_s` of waiting per run; the quietest attempt is kept.
#include <chrono>
#include <iomanip>
#include <iostream>
#include <limits>
#include <string>
#include <thread>
#include <utility>

#include "perf/bench_common.h"

namespace snapfit::bench {

struct QuietGuard {
  bool enabled = true;  // off: one attempt, its contention recorded
  double threshold = 0.25;
  int max_retries = 3;
  double wait_s = 20, budget_s = 600;
  double waited_s = 0;  // over the run so far
  int retries = 0;

  // The quietest of the attempts at `measure()`; the cores other processes kept busy
  // during it into `others`, the number of attempts into `attempts`.
  template <class F>
  auto run(const std::string& what, F&& measure, double& others, int& attempts) -> decltype(measure()) {
    decltype(measure()) best{};
    double best_o = std::numeric_limits<double>::infinity();
    for (int a = 0;; ++a) {
      const CpuSample c0 = cpu_sample();
      auto r = measure();
      const double o = other_cores(c0, cpu_sample());
      if (o < best_o) best = std::move(r), best_o = o;
      attempts = a + 1;
      if (!enabled || o <= threshold || a >= max_retries || waited_s + wait_s > budget_s) break;
      std::cerr << "  (other processes used " << std::fixed << std::setprecision(2) << o << " cores during " << what
                << "; waiting " << std::setprecision(0) << wait_s << " s and measuring it again)\n";
      std::this_thread::sleep_for(std::chrono::duration<double>(wait_s));
      waited_s += wait_s;
      ++retries;
    }
    others = best_o;
    return best;
  }
};

}  // namespace snapfit::bench
