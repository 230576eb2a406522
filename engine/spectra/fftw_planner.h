#pragma once
// FFTW's planner, shared by snapfit's FFTW transforms: it and its wisdom are process-wide
// and not thread-safe, so every plan and destroy holds one lock; plans use all cores.
// Built only when CMake finds FFTW (SNAPFIT_HAVE_FFTW).
#include <mutex>

namespace snapfit {

std::mutex& fftw_planner_lock();
// The threads a plan uses: every core.
int fftw_planner_threads();
// Calls fftwf_plan_with_nthreads(fftw_planner_threads()) for the next plan (under the lock).
void fftw_plan_on_all_cores();

}  // namespace snapfit
