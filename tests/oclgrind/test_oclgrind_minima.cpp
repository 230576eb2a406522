// The map minima kernel (kernels/map_minima.cl, engine/maps/device_minima.h) on Oclgrind with
// its checks on, in the engine's launch and GPU-shaped ones: no report, and the minima
// map_minima finds in the same map on the host (docs/portability.md). Then the search's
// whole device path (product, clFFT's inverse, minima kernel, list read-back) on Oclgrind
// against map_minima on the map that Oclgrind's own clFFT path reads back, and against PoCL.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <doctest/doctest.h>
#include <limits>
#include <random>

#include "engine/maps/device_minima.h"
#include "engine/maps/full_map.h"
#include "engine/maps/map_minima.h"
#include "tests/oclgrind/oclgrind_cases.h"
#include "tests/oclgrind/oclgrind_support.h"
#include "tests/test_engine_support.h"

namespace snapfit::test {
namespace {

bool same_float(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b)); }

void check_same(const MapMinimaResult& got, const MapMinimaResult& want, const std::string& what) {
  INFO(what);
  CHECK(same_float(got.best, want.best));
  REQUIRE(got.minima.size() == want.minima.size());
  for (std::size_t k = 0; k < got.minima.size(); ++k) {
    CHECK(got.minima[k].index == want.minima[k].index);
    CHECK(same_float(got.minima[k].energy, want.minima[k].energy));
  }
}

// Launch shapes of the minima kernel beside the engine's 64 items along x.
struct MinimaShape {
  std::string name, wg;
};
std::vector<MinimaShape> minima_shapes() {
  return {{"64 items along x (the engine's)", "64"},
          {"256 items (longer than a row: most idle)", "256"},
          {"5 items (groups that do not divide a row)", "5"},
          {"1 item per group", "1"}};
}

}  // namespace

TEST_CASE("oclgrind: the map minima kernel in GPU-shaped launches: clean, and the host's minima") {
  // 14 x 13 x 9 points (even and odd axes), coarse values (plateaus), NaN holes, zeros of
  // both signs, in the layout of clFFT's inverse (E = -Re f at FFT node (i + N - N/2) mod N).
  GridSpec g;
  g.dims = Eigen::Vector3i(14, 13, 9);
  g.spacing = 0.5;
  g.origin = -g.spacing * Eigen::Vector3d(7, 6, 4);
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> u(-1.0f, 0.4f);
  std::vector<float> e(g.count());
  for (float& v : e) v = std::round(u(rng) * 8.0f) / 8.0f;
  for (std::size_t i = 0; i < e.size(); i += 7) e[i] = std::nanf("");
  for (std::size_t i = 5; i < e.size(); i += 31)
    if (e[i] == 0.0f) e[i] = -0.0f;
  std::vector<Complex> f(g.count());
  auto node = [](int i, int n) { return std::size_t((i + n - n / 2) % n); };
  for (int z = 0; z < g.dims.z(); ++z)
    for (int y = 0; y < g.dims.y(); ++y)
      for (int x = 0; x < g.dims.x(); ++x)
        f[node(x, 14) + 14 * (node(y, 13) + 13 * node(z, 9))] = Complex(-e[g.index(x, y, z)], 1.0f);
  MapBox box;  // the aliasing box: one face of each axis masked, the other on the grid's edge
  box.lo = {{1, 0, 2}};
  box.hi = {{13, 11, 8}};
  std::vector<float> masked = e;
  for (int z = 0; z < g.dims.z(); ++z)
    for (int y = 0; y < g.dims.y(); ++y)
      for (int x = 0; x < g.dims.x(); ++x)
        if (x < box.lo[0] || x > box.hi[0] || y < box.lo[1] || y > box.hi[1] || z < box.lo[2] || z > box.hi[2])
          masked[g.index(x, y, z)] = std::nanf("");
  MapMinimaResult want;
  map_minima(g, masked, 1000, 0.0, want);
  REQUIRE(want.minima.size() >= 10);
  for (const MinimaShape& shape : minima_shapes()) {
    const std::string what = "map_local_minima, " + shape.name;
    OclgrindSession session(checks_for({"map_local_minima"}));
    const ComputeContext& ctx = session.context();
    EnvScope wg("SNAPFIT_MINIMA_WG", shape.wg.c_str());
    DeviceMinima minima(ctx, {14, 13, 9}, 2, test_program_cache());
    CHECK(minima.work_group() == std::size_t(std::stoi(shape.wg)));
    cl::Buffer map(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * f.size(), f.data());
    MapMinimaResult got[2];
    bool reduced[2] = {false, false};
    for (int slot = 0; slot < 2; ++slot) {
      minima.enqueue_reduce(ctx.queue, slot, map, box);
      cl::Event read;
      minima.enqueue_read(ctx.queue, slot, &read);
      read.wait();
      reduced[slot] = minima.finish(ctx.queue, slot, g, 1000, 0.0, got[slot].minima, got[slot].best);
    }
    expect_clean(session, what);
    for (int slot = 0; slot < 2; ++slot) {
      REQUIRE(reduced[slot]);
      check_same(got[slot], want, what + ", slot " + std::to_string(slot));
    }
  }
}

TEST_CASE("oclgrind: the search's maps with minima on the device: clean, and map_minima on the maps read back") {
  const PairSpectra& pocl = pocl_pair_spectra();
  // The sessions before the FFT library: clFFT's teardown releases what it built for them.
  OclgrindSession session(checks_for({"spectrum_product", "fft_back", "map_local_minima"}));
  const FftLibrary fft;
  std::vector<Eigen::Matrix3d> rotations;
  for (const double angle : {0.0, 0.3, 2.1})
    rotations.push_back(Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 1, 0.5).normalized()).toRotationMatrix());
  std::size_t found = 0;
  for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic}) {
    const std::string what =
        std::string("device minima, ") + (interpolation == Interpolation::tricubic ? "tricubic" : "trilinear");
    TranslationMapper mapper(fft, session.context(), pocl, interpolation, 0, MapFft::clfft, test_program_cache());
    TranslationMapper pocl_mapper(fft, test_context(), pocl, interpolation, 0, MapFft::clfft, test_program_cache());
    const double separation = 2 * pocl.spacing;
    std::vector<float> energy;
    for (std::size_t r = 0; r < rotations.size(); ++r) {
      // Two in flight, as a search runs them: the map read back into slot 0, the minima in slot 1.
      mapper.submit(0, rotations[r], MapOutput::energy);
      mapper.submit(1, rotations[r], MapOutput::minima);
      mapper.collect(0, energy);
      MapMinimaResult want, got, on_pocl;
      map_minima(mapper.grid(), energy, 4, separation, want);
      mapper.collect_minima(1, 4, separation, got);
      check_same(got, want, what + ", rotation " + std::to_string(r));
      // PoCL's device minima of the same map: the same points, energies within float rounding
      // of the two devices' maps (32 ulps of the largest |E|, as the full maps).
      pocl_mapper.submit(0, rotations[r], MapOutput::minima);
      pocl_mapper.collect_minima(0, 4, separation, on_pocl);
      double scale = 0;
      for (float v : energy)
        if (std::isfinite(v)) scale = std::max(scale, double(std::abs(v)));
      REQUIRE(on_pocl.minima.size() == got.minima.size());
      for (std::size_t k = 0; k < got.minima.size(); ++k) {
        CHECK(on_pocl.minima[k].index == got.minima[k].index);
        CHECK(std::abs(double(on_pocl.minima[k].energy) - got.minima[k].energy) <=
              32 * std::numeric_limits<float>::epsilon() * scale);
      }
      found += got.minima.size();
      MESSAGE(what << ", rotation " << r << ": " << got.minima.size() << " minima, lowest E " << got.best);
    }
    CHECK(mapper.minima_counts().on_device == rotations.size());
    CHECK(mapper.minima_counts().fallbacks == 0);
    expect_clean(session, what);
  }
  CHECK(found >= 6);  // the maps hold minima
}

TEST_CASE(
    "oclgrind: a batch of rotations (the product and minima kernels' batched launches): clean, and the same minima") {
  const PairSpectra& pocl = pocl_pair_spectra();
  OclgrindSession session(checks_for({"spectrum_product", "fft_back", "map_local_minima"}));
  const FftLibrary fft;
  std::vector<Eigen::Matrix3d> rotations;
  for (const double angle : {0.3, 2.1})
    rotations.push_back(Eigen::AngleAxisd(angle, Eigen::Vector3d(1, 1, 0.5).normalized()).toRotationMatrix());
  const double separation = 2 * pocl.spacing;
  TranslationMapper batched(fft, session.context(), pocl, Interpolation::trilinear, 0, MapFft::clfft,
                            test_program_cache(), 2);
  TranslationMapper single(fft, test_context(), pocl, Interpolation::trilinear, 0, MapFft::clfft, test_program_cache());
  batched.submit(0, rotations.data(), 2, MapOutput::minima);
  for (std::size_t m = 0; m < 2; ++m) {
    MapMinimaResult got, want;
    batched.collect_minima(0, 4, separation, got, m);
    single.submit(0, rotations[m], MapOutput::minima);
    single.collect_minima(0, 4, separation, want);
    REQUIRE(got.minima.size() == want.minima.size());
    CHECK(!got.minima.empty());
    for (std::size_t k = 0; k < got.minima.size(); ++k) {
      CHECK(got.minima[k].index == want.minima[k].index);
      CHECK(got.minima[k].energy == doctest::Approx(want.minima[k].energy).epsilon(1e-4));
    }
  }
  CHECK(batched.minima_counts().on_device == 2);
  expect_clean(session, "a batch of two rotations");
}

}  // namespace snapfit::test
