#include "engine/spectra/fftw_real_inverse.h"

#include <fftw3.h>
#include <mutex>

#include "core/hash.h"
#include "engine/spectra/fftw_planner.h"
#include "io/cache_file.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr const char* kKind = "snapfit fftw wisdom";
constexpr std::uint32_t kVersion = 1;

std::string wisdom_key(const std::array<std::size_t, 3>& d) {
  return std::string("fftwf ") + fftwf_version + " c2r " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" +
         std::to_string(d[2]) + " threads " + std::to_string(fftw_planner_threads()) + " measure";
}

std::string wisdom_path(const std::string& key) { return cache_root() + "/fftw/" + hex64(fnv1a64(key)) + ".wisdom"; }

}  // namespace

std::string FftwRealInverse::version() { return fftwf_version; }

FftwRealInverse::FftwRealInverse(std::array<std::size_t, 3> dims, int buffers) : dims_(dims) {
  const std::string size = std::to_string(dims[0]) + " x " + std::to_string(dims[1]) + " x " + std::to_string(dims[2]);
  for (int b = 0; b < buffers; ++b) {
    halves_.push_back(reinterpret_cast<std::complex<float>*>(fftwf_alloc_complex(half_count())));
    reals_.push_back(fftwf_alloc_real(count()));
    if (!halves_.back() || !reals_.back()) {
      release();
      throw Error("FFTW: cannot allocate the buffers of a " + size + " transform");
    }
  }
  const std::string key = wisdom_key(dims);
  const std::string path = wisdom_path(key);
  std::lock_guard<std::mutex> lock(fftw_planner_lock());
  fftw_plan_on_all_cores();
  bool from_cache = false;
  if (auto wisdom = read_cache_payload(path, kKind, kVersion, key, "FFTW wisdom", [](const std::string&) {})) {
    wisdom->push_back(0);
    from_cache = fftwf_import_wisdom_from_string(reinterpret_cast<const char*>(wisdom->data())) != 0;
  }
  // FFTW_MEASURE overwrites the arrays while it plans: nothing is in them yet.
  plan_ = fftwf_plan_dft_c2r_3d(int(dims[2]), int(dims[1]), int(dims[0]), reinterpret_cast<fftwf_complex*>(halves_[0]),
                                reals_[0], FFTW_MEASURE);
  if (!plan_) {
    release();
    throw Error("FFTW cannot plan a real inverse FFT of " + size);
  }
  if (char* text = from_cache ? nullptr : fftwf_export_wisdom_to_string()) {
    const std::string wisdom(text);
    fftwf_free(text);
    try {
      write_cache_file(path, kKind, kVersion, key, wisdom.data(), wisdom.size());
    } catch (const Error&) {
      // An unwritable cache only costs the next process its planning time.
    }
  }
}

FftwRealInverse::~FftwRealInverse() { release(); }

void FftwRealInverse::release() {
  if (plan_) {
    std::lock_guard<std::mutex> lock(fftw_planner_lock());
    fftwf_destroy_plan(static_cast<fftwf_plan>(plan_));
    plan_ = nullptr;
  }
  for (auto* p : halves_) fftwf_free(p);
  for (auto* p : reals_) fftwf_free(p);
  halves_.clear();
  reals_.clear();
}

void FftwRealInverse::execute(int buffer) const {
  // The new-array interface: same sizes and alignment (fftwf_alloc) as the planned arrays.
  fftwf_execute_dft_c2r(static_cast<fftwf_plan>(plan_), reinterpret_cast<fftwf_complex*>(halves_[std::size_t(buffer)]),
                        reals_[std::size_t(buffer)]);
}

}  // namespace snapfit
