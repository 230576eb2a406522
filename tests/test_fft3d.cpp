// clFFT 3D transforms (engine/spectra/fft3d.h) against a direct DFT in double precision: the
// independent reference ANCHORS.md asks for (clFFT has had wrong results on PoCL).
#include <cmath>
#include <complex>
#include <doctest/doctest.h>
#include <random>
#include <vector>

#include "engine/runtime/device.h"
#include "engine/spectra/fft3d.h"
#include "snapfit/error.h"

using namespace snapfit;
using cd = std::complex<double>;
using cf = std::complex<float>;

namespace {

// F_k = sum_i f_i exp(sign * 2 pi i (k.i / N)), x fastest.
std::vector<cd> direct_dft(const std::vector<cf>& f, std::array<std::size_t, 3> n, int sign) {
  const std::size_t count = n[0] * n[1] * n[2];
  std::vector<cd> out(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::size_t k0 = k % n[0], k1 = (k / n[0]) % n[1], k2 = k / (n[0] * n[1]);
    cd sum = 0;
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t i0 = i % n[0], i1 = (i / n[0]) % n[1], i2 = i / (n[0] * n[1]);
      // Reduce each product mod N first so the phase stays exact for large k.i.
      const double phase =
          2.0 * M_PI *
          (double((k0 * i0) % n[0]) / n[0] + double((k1 * i1) % n[1]) / n[1] + double((k2 * i2) % n[2]) / n[2]);
      sum += cd(f[i]) * std::polar(1.0, sign * phase);
    }
    out[k] = sum;
  }
  return out;
}

std::vector<cf> random_field(std::size_t count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<cf> f(count);
  for (cf& v : f) v = {u(rng), u(rng)};
  return f;
}

std::vector<cf> run(const Fft3d& fft, const ComputeContext& ctx, FftDirection dir, const std::vector<cf>& in) {
  cl::Buffer a(ctx.context, CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR, sizeof(cf) * in.size(),
               const_cast<cf*>(in.data()));
  cl::Buffer b(ctx.context, CL_MEM_READ_WRITE, sizeof(cf) * in.size());
  fft.transform(dir, a, b);
  std::vector<cf> out(in.size());
  ctx.queue.enqueueReadBuffer(b, CL_TRUE, 0, sizeof(cf) * out.size(), out.data());
  return out;
}

}  // namespace

TEST_CASE("fft: next_fft_size rounds up to sizes with factors 2, 3, 5, 7 only") {
  CHECK(next_fft_size(1) == 1);
  CHECK(next_fft_size(11) == 12);
  CHECK(next_fft_size(13) == 14);
  CHECK(next_fft_size(97) == 98);
  CHECK(next_fft_size(121) == 125);
  CHECK(next_fft_size(128) == 128);
  CHECK(next_fft_size(129) == 135);
  // Even ones, for the spectra's box (engine/spectra/spectra.cpp): 35 and 105 are not.
  CHECK(next_even_fft_size(31) == 32);
  CHECK(next_even_fft_size(33) == 36);
  CHECK(next_even_fft_size(103) == 108);
  CHECK(next_even_fft_size(175) == 180);
  for (std::size_t n = 1; n < 400; ++n) {
    const std::size_t m = next_even_fft_size(n);
    CAPTURE(n);
    CHECK(m >= n);
    CHECK(m % 2 == 0);
    CHECK(next_fft_size(m) == m);
  }
}

TEST_CASE("fft: forward and inverse 3D transforms match a direct DFT in double") {
  const FftLibrary library;
  const ComputeContext ctx = make_compute_context(select_device(""));
  for (const std::array<std::size_t, 3> dims :
       {std::array<std::size_t, 3>{8, 8, 8}, {6, 10, 14}, {12, 5, 9}, {16, 1, 7}}) {
    const Fft3d fft(library, ctx, dims);
    const std::size_t count = fft.count();
    const std::vector<cf> f = random_field(count, 17u + static_cast<unsigned>(count));
    for (const FftDirection dir : {FftDirection::forward, FftDirection::inverse}) {
      const std::vector<cf> got = run(fft, ctx, dir, f);
      const std::vector<cd> want = direct_dft(f, dims, dir == FftDirection::forward ? -1 : +1);
      // Float FFT error grows like eps * log2(N) * sqrt(N) * |f|; |f| <= sqrt(2) per entry.
      double max_err = 0;
      for (std::size_t k = 0; k < count; ++k) max_err = std::max(max_err, std::abs(cd(got[k]) - want[k]));
      const double tolerance = 6e-8 * 8.0 * std::log2(double(count)) * std::sqrt(double(count)) * std::sqrt(2.0);
      MESSAGE(dims[0] << "x" << dims[1] << "x" << dims[2] << (dir == FftDirection::forward ? " forward" : " inverse")
                      << ": max |error| " << max_err << " (tolerance " << tolerance << ")");
      CHECK(max_err <= tolerance);
    }
    // Unnormalized round trip: inverse(forward(f)) = N f.
    const std::vector<cf> back = run(fft, ctx, FftDirection::inverse, run(fft, ctx, FftDirection::forward, f));
    double max_err = 0;
    for (std::size_t i = 0; i < count; ++i)
      max_err = std::max(max_err, std::abs(cd(back[i]) / double(count) - cd(f[i])));
    CHECK(max_err < 1e-5);
  }
}

TEST_CASE("fft: a size with other prime factors is refused with a clear error") {
  const FftLibrary library;
  const ComputeContext ctx = make_compute_context(select_device(""));
  CHECK_THROWS_WITH_AS(Fft3d(library, ctx, {11, 8, 8}), doctest::Contains("11 x 8 x 8"), Error);
}
