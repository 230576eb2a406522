// The pieces of `snapfit search`: map minima against a brute-force reference, the
// mapper's two pipelined slots against single maps, merging, and a whole search plus
// descent on analytic Gaussian parts whose best poses are known in closed form.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <random>

#include "core/so3_grid.h"
#include "engine/runtime/device.h"
#include "engine/maps/full_map.h"
#include "engine/maps/map_minima.h"
#include "engine/query/pose_descent.h"
#include "engine/query/query_engine.h"
#include "engine/maps/rotation_search.h"
#include "snapfit/error.h"
#include "tests/test_cube_grid.h"

using namespace snapfit;

using test::cube_grid;

namespace {

// sign * i * exp(-1/2 (p - m)^T B (p - m)): part 1 with +i and part 2 with -i correlate
// to f = +integral rho1 rho2, so overlap has E = -Re f < 0 like a fit.
std::vector<Complex> gaussian(const GridSpec& g, const Eigen::Vector3d& m, const Eigen::Matrix3d& B, float sign) {
  std::vector<Complex> v(g.count());
  for (std::size_t i = 0; i < g.count(); ++i) {
    const Eigen::Vector3d d = g.point(i) - m;
    v[i] = Complex(0.0f, sign * static_cast<float>(std::exp(-0.5 * d.dot(B * d))));
  }
  return v;
}

// Brute force: every point whose 26 neighbours are all higher (or equal and later),
// sorted, then thinned against every kept one.
std::vector<std::size_t> reference_minima(const GridSpec& g, const std::vector<float>& e, std::size_t count,
                                          double sep) {
  std::vector<std::pair<float, std::size_t>> all;
  for (int z = 0; z < g.dims.z(); ++z)
    for (int y = 0; y < g.dims.y(); ++y)
      for (int x = 0; x < g.dims.x(); ++x) {
        const std::size_t i = g.index(x, y, z);
        if (!(e[i] < 0)) continue;
        bool minimum = true;
        for (int n = 0; n < 27; ++n) {
          const int xx = x + n % 3 - 1, yy = y + n / 3 % 3 - 1, zz = z + n / 9 - 1;
          if (n == 13 || xx < 0 || yy < 0 || zz < 0 || xx >= g.dims.x() || yy >= g.dims.y() || zz >= g.dims.z())
            continue;
          const std::size_t j = g.index(xx, yy, zz);
          if (e[j] < e[i] || (e[j] == e[i] && j < i)) minimum = false;
        }
        if (minimum) all.emplace_back(e[i], i);
      }
  std::sort(all.begin(), all.end());
  std::vector<std::size_t> kept;
  for (const auto& [v, i] : all) {
    bool near = false;
    for (std::size_t k : kept) near = near || (g.point(k) - g.point(i)).norm() <= sep;
    if (!near && kept.size() < count) kept.push_back(i);
  }
  return kept;
}

}  // namespace

TEST_CASE("map minima: the same as a brute-force search, on noise with NaN holes and plateaus") {
  GridSpec g;
  g.dims = Eigen::Vector3i(17, 13, 11);
  g.spacing = 0.5;
  g.origin = Eigen::Vector3d(-4, -3, -2.5);
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 0.3f);
  std::vector<float> e(g.count());
  for (float& v : e) v = std::round(u(rng) * 8.0f) / 8.0f;  // coarse values: many ties
  for (std::size_t i = 0; i < e.size(); i += 7) e[i] = std::nanf("");
  for (const double sep : {0.0, 1.0, 2.6})
    for (const std::size_t count : {1, 5, 1000}) {
      const auto got = map_minima(g, e, count, sep);
      const auto want = reference_minima(g, e, count, sep);
      REQUIRE(got.size() == want.size());
      for (std::size_t k = 0; k < got.size(); ++k) {
        CHECK(got[k].index == want[k]);
        CHECK(got[k].energy == e[want[k]]);
        CHECK((got[k].translation - g.point(want[k])).norm() < 1e-12);
      }
    }
  CHECK_THROWS_AS(map_minima(g, std::vector<float>(3), 1, 0), Error);
}

TEST_CASE("rotation search: pipelined maps equal single maps, and merging does not depend on the order") {
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(select_device(""));
  const double h = 0.25;
  const Eigen::Matrix3d B1 = Eigen::Vector3d(6, 2, 1).asDiagonal();
  const GridSpec g1 = cube_grid(Eigen::Vector3d(0.2, -0.1, 0.3), 24, h), g2 = cube_grid(Eigen::Vector3d::Zero(), 24, h);
  const PairSpectra spectra = compute_pair_spectra(fft, ctx, g1, gaussian(g1, Eigen::Vector3d(0.2, -0.1, 0.3), B1, 1),
                                                   g2, gaussian(g2, Eigen::Vector3d::Zero(), B1, -1));
  TranslationMapper mapper(fft, ctx, spectra, Interpolation::trilinear);
  std::vector<Eigen::Matrix3d> Rs;
  for (double deg : {0.0, 40.0, 130.0})
    Rs.push_back(Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix());
  std::vector<float> a, b, c;
  mapper.submit(0, Rs[0]);
  mapper.submit(1, Rs[1]);
  mapper.collect(1, b);
  mapper.submit(1, Rs[2]);
  mapper.collect(0, a);
  mapper.collect(1, c);
  CHECK_THROWS_AS(mapper.collect(1, c), Error);
  for (std::size_t r = 0; r < 3; ++r) {
    const TranslationMap single = translational_energy_map(fft, ctx, spectra, Rs[r], Interpolation::trilinear);
    const std::vector<float>& got = r == 0 ? a : r == 1 ? b : c;
    REQUIRE(got.size() == single.energy.size());
    std::size_t same = 0;
    for (std::size_t i = 0; i < got.size(); ++i)
      same += got[i] == single.energy[i] || (std::isnan(got[i]) && std::isnan(single.energy[i]));
    CHECK(same == got.size());
  }

  const So3Grid grid = so3_grid_for_count(60);
  std::vector<std::size_t> all(grid.rotations.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const RotationScan scan = scan_rotations(mapper, grid.rotations, all, ScanOptions{3, 2 * h});
  CHECK(scan.rotations == all);
  const auto merged = merge_candidates(scan.candidates, 8, 2 * h, grid.step_rad);
  std::vector<PoseCandidate> shuffled = scan.candidates;
  std::shuffle(shuffled.begin(), shuffled.end(), std::mt19937(9));
  const auto again = merge_candidates(shuffled, 8, 2 * h, grid.step_rad);
  REQUIRE(merged.size() == again.size());
  for (std::size_t k = 0; k < merged.size(); ++k) {
    CHECK(merged[k].rotation == again[k].rotation);
    CHECK(merged[k].cell == again[k].cell);
    if (k > 0) CHECK(merged[k].energy >= merged[k - 1].energy);
    for (std::size_t j = 0; j < k; ++j)
      CHECK(((merged[j].pose.translation - merged[k].pose.translation).norm() > 2 * h ||
             rotation_distance(merged[j].pose.rotation, merged[k].pose.rotation) > grid.step_rad));
  }
}

TEST_CASE("rotation search: anisotropic Gaussians are found aligned, and the descent reaches the closed form") {
  // Part 1: B at m1. Part 2: the same B at its own origin. The overlap integral peaks
  // where R B R^T = B and R 0 + t = m1: R = I or a half turn about a principal axis.
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(select_device(""));
  const double h = 0.25;
  const Eigen::Vector3d m1(0.6, -0.4, 0.3);
  const Eigen::Matrix3d B = Eigen::Vector3d(6, 2, 0.9).asDiagonal();
  const GridSpec g1 = cube_grid(m1, 28, h), g2 = cube_grid(Eigen::Vector3d::Zero(), 28, h);
  const PairSpectra spectra =
      compute_pair_spectra(fft, ctx, g1, gaussian(g1, m1, B, 1), g2, gaussian(g2, Eigen::Vector3d::Zero(), B, -1));
  TranslationMapper mapper(fft, ctx, spectra, Interpolation::tricubic);
  const So3Grid grid = so3_grid_for_count(72);
  std::vector<std::size_t> all(grid.rotations.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  const RotationScan scan = scan_rotations(mapper, grid.rotations, all, ScanOptions{2, 2 * h});
  const auto top = merge_candidates(scan.candidates, 4, 2 * h, grid.step_rad);
  REQUIRE(!top.empty());
  auto symmetric_distance = [](const Eigen::Quaterniond& q) {
    double d = M_PI;
    for (const Eigen::Quaterniond& s : {Eigen::Quaterniond::Identity(), Eigen::Quaterniond(0, 1, 0, 0),
                                        Eigen::Quaterniond(0, 0, 1, 0), Eigen::Quaterniond(0, 0, 0, 1)})
      d = std::min(d, rotation_distance(q, s));
    return d;
  };
  const double cover = so3_covering_radius(grid, 20000);
  // The grid holds I and the half turn about z; the first pose is one of the four (the
  // others are as good), within a grid step of translation.
  CHECK(symmetric_distance(top[0].pose.rotation) <= cover);
  CHECK((top[0].pose.translation - m1).norm() <= 2 * h);
  // Descent from a pose off by 12 degrees and 0.4 units converges to the aligned pose.
  auto engine = make_query_engine(ctx, spectra, QueryVariant{true, true, false, Interpolation::tricubic});
  engine->set_modes(32768);
  Pose start;
  start.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(12 * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized()));
  start.translation = m1 + Eigen::Vector3d(0.3, -0.2, 0.2);
  DescentOptions options;
  options.length = 1.0;
  options.step = h;
  options.min_step = 1e-4;
  options.max_queries = 300;
  const DescentResult r = descend_pose(*engine, start, options);
  MESSAGE("descent: " << r.queries << " queries, " << symmetric_distance(r.pose.rotation) * 180 / M_PI << " deg, "
                      << (r.pose.translation - m1).norm() << " from the closed form");
  CHECK(symmetric_distance(r.pose.rotation) < 1.0 * M_PI / 180);
  CHECK((r.pose.translation - m1).norm() < 0.02);
  CHECK(r.energy < engine->query(start).energy);
  Pose outside;
  outside.translation = Eigen::Vector3d(100, 0, 0);
  CHECK_THROWS_AS(descend_pose(*engine, outside, options), Error);
}
