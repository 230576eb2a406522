// The inverse FFT of full maps chosen by measurement (engine/maps/map_fft_choice.h): every
// backend built is timed, the fastest is picked, and the pick is read back from the
// cache on the next call; names parse both ways.
#include <algorithm>
#include <doctest/doctest.h>

#include "engine/runtime/device.h"
#include "engine/maps/map_fft_choice.h"
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
  // Each backend one rotation at a time, then the device FFTs in batches.
  std::vector<std::pair<MapFft, std::size_t>> tried;
  for (const MapFft f : map_ffts_built()) tried.push_back({f, 1});
  const std::size_t batch = map_batch_limit(ctx, spectra.dims, kMapBatch);
  CHECK(batch == kMapBatch);  // a 12^3 map fits any device many times over
  for (const MapFft f : map_ffts_built())
    if (map_fft_on_device(f)) tried.push_back({f, batch});
  REQUIRE(first.timings.size() == tried.size());
  double best = 1e300;
  for (std::size_t i = 0; i < first.timings.size(); ++i) {
    CHECK(first.timings[i].fft == tried[i].first);
    CHECK(first.timings[i].batch == tried[i].second);
    CHECK(first.timings[i].seconds > 0);
    best = std::min(best, first.timings[i].seconds);
  }
  std::size_t picked = 0;
  for (const MapFftTiming& t : first.timings)
    if (t.fft == first.fft && t.batch == first.batch) {
      CHECK(t.seconds == best);
      ++picked;
    }
  CHECK(picked == 1);
  MESSAGE(describe_map_fft_choice(first));

  const MapFftChoice again = choose_map_fft(fft, ctx, spectra, Interpolation::trilinear);
  CHECK(again.cached);
  CHECK(again.fft == first.fft);
  CHECK(again.batch == first.batch);
  REQUIRE(again.timings.size() == first.timings.size());
  for (std::size_t i = 0; i < again.timings.size(); ++i) CHECK(again.timings[i].seconds == first.timings[i].seconds);
  CHECK(describe_map_fft_choice(again).find("cached") != std::string::npos);
}

TEST_CASE("map FFT names: each backend built parses back, an unknown name is an error naming it") {
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
