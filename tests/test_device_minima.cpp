// The minima of full maps found on the device (engine/maps/device_minima.h, kernels/map_minima.cl)
// against the host's map_minima on the whole map, the reference: the same minima in the
// same order with the same energies, and the same lowest energy, bit for bit. On
// synthetic maps (plateaus, NaN holes and masked slabs, minima on the grid's faces,
// zeros of both signs, infinities, lists longer than the first read and than the buffer)
// and on the maps of the shipped default scene, through TranslationMapper's two slots and
// scan_rotations.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <doctest/doctest.h>
#include <memory>
#include <random>

#include "core/so3_grid.h"
#include "engine/maps/device_minima.h"
#include "engine/maps/full_map.h"
#include "engine/maps/map_minima.h"
#include "engine/maps/rotation_search.h"
#include "engine/spectra/spectra.h"
#include "pipeline/assembly_pair.h"
#include "tests/shipped_engine.h"
#include "tests/test_engine_support.h"

using namespace snapfit;

namespace {

bool same_float(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0 || (std::isnan(a) && std::isnan(b)); }

// The device's result against the reference, entry by entry.
void check_same(const MapMinimaResult& got, const MapMinimaResult& want, const std::string& what) {
  INFO(what);
  CHECK(same_float(got.best, want.best));
  REQUIRE(got.minima.size() == want.minima.size());
  for (std::size_t k = 0; k < got.minima.size(); ++k) {
    INFO("minimum " << k);
    CHECK(got.minima[k].index == want.minima[k].index);
    CHECK(same_float(got.minima[k].energy, want.minima[k].energy));
    CHECK(got.minima[k].translation == want.minima[k].translation);
  }
}

// A map given in grid order, laid out as clFFT's inverse FFT holds it: E = -Re f at FFT
// node (x + N - N/2) mod N per axis (engine/maps/full_map.cpp), Im f some other value.
std::vector<Complex> fft_layout(const GridSpec& g, const std::vector<float>& energy) {
  std::vector<Complex> f(g.count());
  for (int z = 0; z < g.dims.z(); ++z)
    for (int y = 0; y < g.dims.y(); ++y)
      for (int x = 0; x < g.dims.x(); ++x) {
        auto node = [](int i, int n) { return std::size_t((i + n - n / 2) % n); };
        const std::size_t j =
            node(x, g.dims.x()) + std::size_t(g.dims.x()) * (node(y, g.dims.y()) + g.dims.y() * node(z, g.dims.z()));
        const float e = energy[g.index(x, y, z)];
        f[j] = Complex(-e, 0.5f * float(x) - e);
      }
  return f;
}

// The reference: the map masked to the box (NaN outside), then map_minima on the host.
MapMinimaResult host_reference(const GridSpec& g, std::vector<float> energy, const MapBox& box, std::size_t count,
                               double separation) {
  for (int z = 0; z < g.dims.z(); ++z)
    for (int y = 0; y < g.dims.y(); ++y)
      for (int x = 0; x < g.dims.x(); ++x)
        if (x < box.lo[0] || x > box.hi[0] || y < box.lo[1] || y > box.hi[1] || z < box.lo[2] || z > box.hi[2])
          energy[g.index(x, y, z)] = std::nanf("");
  MapMinimaResult out;
  map_minima(g, energy, count, separation, out);
  return out;
}

struct DeviceRun {
  bool reduced = false;
  MapMinimaResult result;
};

DeviceRun device_run(DeviceMinima& minima, const GridSpec& g, const std::vector<float>& energy, const MapBox& box,
                     std::size_t count, double separation, int slot = 0) {
  const ComputeContext& ctx = test::test_context();
  std::vector<Complex> f = fft_layout(g, energy);
  cl::Buffer map(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * f.size(), f.data());
  minima.enqueue_reduce(ctx.queue, slot, map, box);
  cl::Event read;
  minima.enqueue_read(ctx.queue, slot, &read);
  read.wait();
  DeviceRun run;
  run.result.best = -12345.0f;  // left as it was when not reduced
  run.reduced = minima.finish(ctx.queue, slot, g, count, separation, run.result.minima, run.result.best);
  return run;
}

GridSpec grid_of(int nx, int ny, int nz) {
  GridSpec g;
  g.dims = Eigen::Vector3i(nx, ny, nz);
  g.spacing = 0.5;
  g.origin = -g.spacing * Eigen::Vector3d(nx / 2, ny / 2, nz / 2);
  return g;
}

MapBox full_box(const GridSpec& g) {
  MapBox b;
  b.hi = {{g.dims.x() - 1, g.dims.y() - 1, g.dims.z() - 1}};
  return b;
}

}  // namespace

TEST_CASE("device minima: synthetic maps with plateaus, NaN holes, masked slabs and edges equal map_minima") {
  // Even and odd axes (the FFT shift N/2 differs), coarse values (many ties: plateaus),
  // NaN holes, zeros of both signs.
  const GridSpec g = grid_of(16, 13, 11);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 0.4f);
  std::vector<float> e(g.count());
  for (float& v : e) v = std::round(u(rng) * 8.0f) / 8.0f;
  for (std::size_t i = 0; i < e.size(); i += 7) e[i] = std::nanf("");
  for (std::size_t i = 3; i < e.size(); i += 29)
    if (e[i] == 0.0f) e[i] = -0.0f;
  // A wide plateau through a face, and a single deep minimum in a corner.
  for (int z = 2; z < 6; ++z)
    for (int y = 0; y < 4; ++y)
      for (int x = 5; x < 11; ++x) e[g.index(x, y, z)] = -2.0f;
  e[g.index(g.dims.x() - 1, g.dims.y() - 1, g.dims.z() - 1)] = -3.0f;
  DeviceMinima minima(test::test_context(), {16, 13, 11}, 2, test::test_program_cache());
  std::vector<MapBox> boxes{full_box(g)};
  MapBox inner;
  inner.lo = {{1, 0, 2}};
  inner.hi = {{13, 12, 8}};
  boxes.push_back(inner);
  MapBox slab;  // one plane of x
  slab.lo = {{4, 0, 0}};
  slab.hi = {{4, 12, 10}};
  boxes.push_back(slab);
  boxes.push_back(MapBox{});  // everything aliases
  std::size_t nonempty = 0;
  for (const MapBox& box : boxes)
    for (const double sep : {0.0, 1.0, 2.6})
      for (const std::size_t count : {std::size_t(0), std::size_t(1), std::size_t(5), std::size_t(1000)}) {
        const MapMinimaResult want = host_reference(g, e, box, count, sep);
        const DeviceRun got = device_run(minima, g, e, box, count, sep, int(count % 2));
        REQUIRE(got.reduced);
        check_same(got.result, want,
                   "box " + std::to_string(box.lo[0]) + ".." + std::to_string(box.hi[0]) + ", separation " +
                       std::to_string(sep) + ", count " + std::to_string(count));
        nonempty += !want.minima.empty();
      }
  CHECK(nonempty >= 20);  // the cases hold minima
  CHECK(minima.stats().overflows == 0);
  CHECK(minima.stats().infinities == 0);
}

TEST_CASE("device minima: the lowest energy without negative minima, zeros of either sign, and no finite point") {
  const GridSpec g = grid_of(9, 8, 7);
  DeviceMinima minima(test::test_context(), {9, 8, 7}, 1, test::test_program_cache());
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 2.0f);
  std::vector<float> positive(g.count());
  for (float& v : positive) v = 0.25f + std::round(u(rng) * 4.0f) / 4.0f;
  // Zeros: the first in grid order is -0 in one map, +0 in the other (the host's lowest E
  // is the first zero it meets).
  for (const float first_zero : {-0.0f, 0.0f}) {
    std::vector<float> zeros = positive;
    zeros[g.index(3, 2, 1)] = first_zero;
    zeros[g.index(6, 5, 4)] = -first_zero;
    for (const std::vector<float>* map : {&positive, &zeros}) {
      const MapMinimaResult want = host_reference(g, *map, full_box(g), 4, 1.0);
      const DeviceRun got = device_run(minima, g, *map, full_box(g), 4, 1.0);
      REQUIRE(got.reduced);
      CHECK(want.minima.empty());
      CHECK(std::isfinite(want.best));
      CHECK(std::signbit(want.best) == std::signbit(got.result.best));
      check_same(got.result, want, map == &positive ? "positive map" : "map with zeros");
    }
  }
  std::vector<float> nan(g.count(), std::nanf(""));
  const DeviceRun got = device_run(minima, g, nan, full_box(g), 4, 1.0);
  REQUIRE(got.reduced);
  CHECK(std::isnan(got.result.best));
  CHECK(got.result.minima.empty());
}

TEST_CASE("device minima: infinities and overflowing lists are reported, long lists read in full") {
  const GridSpec g = grid_of(40, 36, 30);
  std::mt19937 rng(8);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> noise(g.count());
  for (float& v : noise) v = u(rng);  // random noise: about 1 point in 27 is a minimum
  {
    DeviceMinima minima(test::test_context(), {40, 36, 30}, 2, test::test_program_cache());
    for (int pass = 0; pass < 2; ++pass) {
      const MapMinimaResult want = host_reference(g, noise, full_box(g), 100000, 0.0);
      const DeviceRun got = device_run(minima, g, noise, full_box(g), 100000, 0.0, pass);
      REQUIRE(got.reduced);
      REQUIRE(want.minima.size() > 1024);  // longer than the first read
      check_same(got.result, want, "noise, pass " + std::to_string(pass));
    }
    // The first list was read in two parts, the second at once.
    CHECK(minima.stats().long_lists == 1);
    CHECK(minima.stats().longest > 1024);
    for (const float inf : {INFINITY, -INFINITY}) {
      std::vector<float> with_inf = noise;
      with_inf[g.index(20, 18, 15)] = inf;
      const DeviceRun got = device_run(minima, g, with_inf, full_box(g), 4, 1.0);
      CHECK_FALSE(got.reduced);
      CHECK(got.result.best == -12345.0f);  // untouched
    }
    CHECK(minima.stats().infinities == 2);
    // An infinity outside the box is not in the map.
    MapBox box = full_box(g);
    box.hi[0] = 19;
    std::vector<float> masked_inf = noise;
    masked_inf[g.index(20, 18, 15)] = INFINITY;
    const DeviceRun masked = device_run(minima, g, masked_inf, box, 4, 1.0);
    REQUIRE(masked.reduced);
    check_same(masked.result, host_reference(g, noise, box, 4, 1.0), "infinity outside the box");
  }
  {
    test::EnvScope capacity("SNAPFIT_MINIMA_CAPACITY", "100");
    DeviceMinima minima(test::test_context(), {40, 36, 30}, 1, test::test_program_cache());
    CHECK(minima.capacity() == 100);
    const DeviceRun got = device_run(minima, g, noise, full_box(g), 4, 1.0);
    CHECK_FALSE(got.reduced);
    CHECK(minima.stats().overflows == 1);
    CHECK(minima.stats().longest > 100);  // the count goes on past the list's end
  }
  // The default capacity is the most minima a map can have: a checkerboard of 2 x 2 x 2
  // blocks, one minimum each, fills it exactly.
  const GridSpec small = grid_of(7, 6, 5);
  DeviceMinima exact(test::test_context(), {7, 6, 5}, 1, test::test_program_cache());
  CHECK(exact.capacity() == 4 * 3 * 3);
  std::vector<float> blocks(small.count(), 1.0f);
  for (int z = 0; z < 5; z += 2)
    for (int y = 0; y < 6; y += 2)
      for (int x = 0; x < 7; x += 2) blocks[small.index(x, y, z)] = -1.0f - 0.01f * float(x + 7 * y + 42 * z);
  const DeviceRun full = device_run(exact, small, blocks, full_box(small), 1000, 0.0);
  REQUIRE(full.reduced);
  CHECK(full.result.minima.size() == exact.capacity());
  check_same(full.result, host_reference(small, blocks, full_box(small), 1000, 0.0), "checkerboard");
}

// The shipped default scene's pair, fields and spectra through the caches.
static AssemblyPair default_scene_pair(const FftLibrary& fft) {
  PairOptions options;
  options.note = [](const std::string&) {};
  return build_assembly_pair(test::shipped_scene("default.json"), test::test_context(), fft, options);
}

TEST_CASE("device minima: the shipped default scene's maps, pipelined, equal map_minima on the maps read back") {
  const FftLibrary fft;
  const AssemblyPair pair = default_scene_pair(fft);
  const PairSpectra& spectra = pair.spectra;
  const double separation = 2 * spectra.spacing;
  const So3Grid grid = so3_grid_for_count(24);
  std::vector<std::size_t> picked{0, 5, 11, 17, 23};
  std::vector<Eigen::Quaterniond> rotations;
  for (std::size_t i : picked) rotations.push_back(grid.rotations[i]);
  if (pair.scene.assembled_pose) rotations.push_back(pair.scene.assembled_pose->rotation);
  // Every device FFT built (clFFT, VkFFT), each against its own maps read back.
  std::unique_ptr<TranslationMapper> clfft_mapper;
  std::vector<MapMinimaResult> clfft_every, clfft_top;  // for the checks after
  for (const MapFft kind : map_ffts_built()) {
    if (!map_fft_on_device(kind)) continue;
    auto mapper = std::make_unique<TranslationMapper>(fft, test::test_context(), spectra, Interpolation::trilinear, 0,
                                                      kind, test::test_program_cache());
    REQUIRE(mapper->minima_on_device());
    // The reference: each whole map read back, map_minima on the host.
    std::vector<MapMinimaResult> every, top;
    std::vector<float> energy;
    for (const Eigen::Quaterniond& q : rotations) {
      mapper->submit(0, q.toRotationMatrix(), MapOutput::energy);
      mapper->collect(0, energy);
      every.emplace_back();
      map_minima(mapper->grid(), energy, 1000000, 0.0, every.back());
      top.emplace_back();
      map_minima(mapper->grid(), energy, 4, separation, top.back());
    }
    // Device minima, two maps in flight: every minimum, and the search's four.
    std::size_t total = 0;
    for (const bool all : {true, false}) {
      const std::size_t count = all ? 1000000 : 4;
      const double sep = all ? 0.0 : separation;
      const std::vector<MapMinimaResult>& want = all ? every : top;
      MapMinimaResult got;
      mapper->submit(0, rotations[0].toRotationMatrix(), MapOutput::minima);
      mapper->submit(1, rotations[1].toRotationMatrix(), MapOutput::minima);
      CHECK_THROWS_AS(mapper->collect(0, energy), Error);  // submitted for its minima
      for (std::size_t i = 0; i < rotations.size(); ++i) {
        mapper->collect_minima(int(i % 2), count, sep, got);
        if (i + 2 < rotations.size())
          mapper->submit(int(i % 2), rotations[i + 2].toRotationMatrix(), MapOutput::minima);
        check_same(got, want[i],
                   map_fft_name(kind) + (all ? ", every minimum" : ", top 4") + ", rotation " + std::to_string(i));
        if (all) total += got.minima.size();
      }
    }
    const MapMinimaCounts counts = mapper->minima_counts();
    MESSAGE(map_fft_name(kind) << ", default scene, " << mapper->grid().dims.transpose() << " translations: " << total
                               << " minima in " << rotations.size() << " maps, longest list " << counts.longest << ", "
                               << counts.long_lists << " lists longer than their first read");
    CHECK(total >= rotations.size());
    CHECK(counts.on_device == 2 * rotations.size());
    CHECK(counts.fallbacks == 0);
    if (kind == MapFft::clfft) {
      clfft_mapper = std::move(mapper);
      clfft_every = every;
      clfft_top = top;
    }
  }
  REQUIRE(clfft_mapper);
  TranslationMapper& mapper = *clfft_mapper;
  const std::vector<MapMinimaResult>& every = clfft_every;
  const std::vector<MapMinimaResult>& top = clfft_top;

  // scan_rotations (device minima) gives the reference's candidates and lowest energies.
  std::vector<std::size_t> indices(rotations.size());
  for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
  const RotationScan scan = scan_rotations(mapper, rotations, indices, ScanOptions{4, separation});
  std::size_t c = 0;
  for (std::size_t i = 0; i < rotations.size(); ++i) {
    CHECK(same_float(float(scan.best_energy[i]), top[i].best));
    for (const MapMinimum& m : top[i].minima) {
      REQUIRE(c < scan.candidates.size());
      CHECK(scan.candidates[c].rotation == i);
      CHECK(scan.candidates[c].cell == m.index);
      CHECK(scan.candidates[c].energy == double(m.energy));
      ++c;
    }
  }
  CHECK(c == scan.candidates.size());

  // A list too small for the maps: each map falls back to the whole map, with the same result.
  test::EnvScope capacity("SNAPFIT_MINIMA_CAPACITY", "2");
  TranslationMapper small(fft, test::test_context(), spectra, Interpolation::trilinear, 0, MapFft::clfft,
                          test::test_program_cache());
  MapMinimaResult got;
  for (std::size_t i = 0; i < 2; ++i) {
    small.submit(0, rotations[i].toRotationMatrix(), MapOutput::minima);
    small.collect_minima(0, 1000000, 0.0, got);
    check_same(got, every[i], "capacity 2, rotation " + std::to_string(i));
  }
  CHECK(small.minima_counts().fallbacks == 2);
  CHECK(small.minima_counts().on_host == 2);
}

TEST_CASE(
    "device minima: batches of rotations on the shipped default scene give the maps and minima of one at a time") {
  const FftLibrary fft;
  const AssemblyPair pair = default_scene_pair(fft);
  const PairSpectra& spectra = pair.spectra;
  const double separation = 2 * spectra.spacing;
  const So3Grid grid = so3_grid_for_count(24);
  // Seven rotations in batches of three: two full batches and a batch of one.
  std::vector<Eigen::Quaterniond> rotations;
  for (std::size_t i : {0, 3, 7, 11, 15, 19, 23}) rotations.push_back(grid.rotations[i]);
  std::vector<std::size_t> indices(rotations.size());
  for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = i;
  for (const MapFft kind : map_ffts_built()) {
    if (!map_fft_on_device(kind)) {
      CHECK_THROWS_WITH_AS(TranslationMapper(fft, test::test_context(), spectra, Interpolation::trilinear, 0, kind,
                                             test::test_program_cache(), 2),
                           doctest::Contains("batch of 2"), Error);
      continue;
    }
    TranslationMapper one(fft, test::test_context(), spectra, Interpolation::trilinear, 0, kind,
                          test::test_program_cache());
    TranslationMapper three(fft, test::test_context(), spectra, Interpolation::trilinear, 0, kind,
                            test::test_program_cache(), 3);
    CHECK(three.batch() == 3);
    const std::string name = map_fft_name(kind);
    // The maps: member m of a batch against the same rotation mapped alone. A batched
    // transform may round differently, so within float rounding of the map's scale.
    std::vector<Eigen::Matrix3d> R;
    for (std::size_t i = 0; i < 3; ++i) R.push_back(rotations[i].toRotationMatrix());
    three.submit(1, R.data(), 3, MapOutput::energy);
    std::vector<float> alone, member;
    for (std::size_t m : {2, 0, 1}) {  // members in any order
      one.submit(0, R[m], MapOutput::energy);
      one.collect(0, alone);
      three.collect(1, member, m);
      REQUIRE(member.size() == alone.size());
      double scale = 0, worst = 0;
      std::size_t same_nan = 0;
      for (std::size_t i = 0; i < alone.size(); ++i) {
        if (std::isnan(alone[i]) || std::isnan(member[i])) {
          same_nan += std::isnan(alone[i]) && std::isnan(member[i]);
          continue;
        }
        scale = std::max(scale, double(std::abs(alone[i])));
        worst = std::max(worst, double(std::abs(member[i] - alone[i])));
      }
      CHECK(same_nan == std::size_t(std::count_if(alone.begin(), alone.end(), [](float e) { return std::isnan(e); })));
      CHECK(scale > 0);
      CHECK(worst <= 1e-5 * scale);
      MESSAGE(name << " batch member " << m << ": largest difference " << worst << " of " << scale);
    }
    CHECK_THROWS_AS(three.collect(1, member, 0), Error);  // collected already
    three.submit(0, R.data(), 1, MapOutput::energy);
    CHECK_THROWS_AS(three.collect(0, member, 1), Error);  // not submitted
    CHECK_THROWS_AS(three.submit(0, R.data(), 0), Error);
    CHECK_THROWS_AS(three.submit(0, R.data(), 4), Error);

    // The search's scan: the same candidates, rotation by rotation.
    const RotationScan a = scan_rotations(one, rotations, indices, ScanOptions{4, separation});
    const RotationScan b = scan_rotations(three, rotations, indices, ScanOptions{4, separation});
    CHECK(b.rotations == a.rotations);
    REQUIRE(b.candidates.size() == a.candidates.size());
    for (std::size_t k = 0; k < a.candidates.size(); ++k) {
      CHECK(b.candidates[k].rotation == a.candidates[k].rotation);
      CHECK(b.candidates[k].cell == a.candidates[k].cell);
      CHECK(b.candidates[k].energy == doctest::Approx(a.candidates[k].energy).epsilon(1e-4));
    }
    for (std::size_t i = 0; i < rotations.size(); ++i)
      CHECK(b.best_energy[i] == doctest::Approx(a.best_energy[i]).epsilon(1e-4));
    CHECK(three.minima_counts().on_device >= rotations.size());
    CHECK(three.minima_counts().fallbacks == 0);
  }
}
