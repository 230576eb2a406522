#include "engine/spectra/fftw_planner.h"

#include <algorithm>
#include <fftw3.h>
#include <thread>

namespace snapfit {

std::mutex& fftw_planner_lock() {
  static std::mutex lock;
  return lock;
}

int fftw_planner_threads() { return int(std::max(1u, std::thread::hardware_concurrency())); }

void fftw_plan_on_all_cores() {
  static const bool with_threads = fftwf_init_threads() != 0;
  if (with_threads) fftwf_plan_with_nthreads(fftw_planner_threads());
}

}  // namespace snapfit
