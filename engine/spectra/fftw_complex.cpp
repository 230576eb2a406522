#include "engine/spectra/fftw_complex.h"

#include <fftw3.h>
#include <string>

#include "engine/spectra/fftw_planner.h"
#include "snapfit/error.h"

namespace snapfit {

void fftw_complex_in_place(std::vector<std::complex<float>>& data, const std::array<std::size_t, 3>& dims,
                           bool inverse) {
  const std::string size = std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]);
  if (data.size() != dims[0] * dims[1] * dims[2] || data.empty())
    throw Error("FFTW FFT of " + size + ": " + std::to_string(data.size()) + " values given");
  auto* values = reinterpret_cast<fftwf_complex*>(data.data());
  fftwf_plan plan = nullptr;
  {
    std::lock_guard<std::mutex> lock(fftw_planner_lock());
    fftw_plan_on_all_cores();
    // FFTW_ESTIMATE leaves the array as it is while planning.
    plan = fftwf_plan_dft_3d(int(dims[2]), int(dims[1]), int(dims[0]), values, values,
                             inverse ? FFTW_BACKWARD : FFTW_FORWARD, FFTW_ESTIMATE);
  }
  if (!plan) throw Error("FFTW cannot plan an FFT of " + size);
  fftwf_execute(plan);
  std::lock_guard<std::mutex> lock(fftw_planner_lock());
  fftwf_destroy_plan(plan);
}

}  // namespace snapfit
