// The inverse FFT of full maps chosen by measurement (engine/map_fft_choice.h): every
// backend built is timed, the fastest is picked, and the pick is read back from the
// cache on the next call; names parse both ways.
#include <algorithm>
#include <doctest/doctest.h>

#include "engine/device.h"
#include "engine/map_fft_choice.h"
#include "snapfit/error.h"
#include "tests/test_cube_grid.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

std::vector<Complex> blob(const GridSpec& g, const Eigen::Vector3d& m) {
  std::vector<Complex> v(g.count());
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i)
        v[g.index(i, j, k)] = Complex(0.0f, float(std::exp(-(g.point(i, j, k) - m).squaredNorm())));
  return v;
}

}  // namespace

TEST_CASE("map FFT choice: every backend built is measured, the fastest kept, then read from the cache") {
  test::CacheDirScope cache;
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(select_device(""));
  const Eigen::Vector3d m(0.1, 0.2, -0.1);
  const GridSpec g = test::cube_grid(m, 12, 0.3);
  const PairSpectra spectra = compute_pair_spectra(fft, ctx, g, blob(g, m), g, blob(g, m));
  const MapFftChoice first = choose_map_fft(fft, ctx, spectra, Interpolation::trilinear);
  CHECK_FALSE(first.cached);
  REQUIRE(first.timings.size() == map_ffts_built().size());
  double best = 1e300;
  for (std::size_t i = 0; i < first.timings.size(); ++i) {
    CHECK(first.timings[i].fft == map_ffts_built()[i]);
    CHECK(first.timings[i].seconds > 0);
    best = std::min(best, first.timings[i].seconds);
  }
  for (const MapFftTiming& t : first.timings)
    if (t.fft == first.fft) CHECK(t.seconds == best);
  MESSAGE(describe_map_fft_choice(first));

  const MapFftChoice again = choose_map_fft(fft, ctx, spectra, Interpolation::trilinear);
  CHECK(again.cached);
  CHECK(again.fft == first.fft);
  REQUIRE(again.timings.size() == first.timings.size());
  for (std::size_t i = 0; i < again.timings.size(); ++i) CHECK(again.timings[i].seconds == first.timings[i].seconds);
  CHECK(describe_map_fft_choice(again).find("cached") != std::string::npos);
}

TEST_CASE("map FFT names: each backend built parses back; an unknown name is an error naming it") {
  for (const MapFft f : map_ffts_built()) CHECK(parse_map_fft(map_fft_name(f)) == f);
  CHECK(map_ffts_built().front() == MapFft::clfft);
  CHECK_THROWS_WITH_AS(parse_map_fft("cufft"), doctest::Contains("cufft"), Error);
  // The optional backends this build lacks are named with the package that brings them.
  for (const MapFft f : {MapFft::fftw, MapFft::vkfft}) {
    const auto built = map_ffts_built();
    if (std::find(built.begin(), built.end(), f) == built.end())
      CHECK_THROWS_WITH_AS(parse_map_fft(map_fft_name(f)), doctest::Contains("this build has no"), Error);
  }
  CHECK(map_fft_on_device(MapFft::clfft));
  CHECK(map_fft_on_device(MapFft::vkfft));
  CHECK_FALSE(map_fft_on_device(MapFft::fftw));
}
