// Full translational maps (engine/full_map.h) against per-pose queries at the same
// grid translations, rotation and interpolation, on analytic Gaussian fields.
#include <cmath>
#include <doctest/doctest.h>

#include "engine/device.h"
#include "engine/full_map.h"
#include "engine/query_engine.h"
#include "tests/test_cube_grid.h"

using namespace snapfit;

using test::cube_grid;

namespace {

// i * exp(-1/2 (p - m)^T B (p - m)) sampled on the grid.
std::vector<Complex> gaussian(const GridSpec& g, const Eigen::Vector3d& m, const Eigen::Matrix3d& B) {
  std::vector<Complex> v(g.count());
  for (int k = 0; k < g.dims.z(); ++k)
    for (int j = 0; j < g.dims.y(); ++j)
      for (int i = 0; i < g.dims.x(); ++i) {
        const Eigen::Vector3d d = g.point(i, j, k) - m;
        v[g.index(i, j, k)] = Complex(0.0f, static_cast<float>(std::exp(-0.5 * d.dot(B * d))));
      }
  return v;
}

}  // namespace

TEST_CASE("full map: every translation of the map equals a per-pose query there") {
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(select_device(""));
  const double h = 0.25;
  const Eigen::Vector3d m1(0.2, -0.1, 0.3), m2(0.4, 0.3, -0.2);
  const Eigen::Matrix3d B1 = Eigen::Vector3d(1.5, 1.0, 0.8).asDiagonal();
  const Eigen::Matrix3d B2 = Eigen::Vector3d(3.0, 1.2, 0.7).asDiagonal();
  const GridSpec g1 = cube_grid(m1, 24, h), g2 = cube_grid(m2, 20, h);
  const PairSpectra spectra = compute_pair_spectra(fft, ctx, g1, gaussian(g1, m1, B1), g2, gaussian(g2, m2, B2));
  for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic}) {
    for (const double degrees : {0.0, 35.0, 170.0}) {
      const Eigen::Matrix3d R =
          Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
      const TranslationMap map = translational_energy_map(fft, ctx, spectra, R, interpolation);
      auto engine = make_query_engine(ctx, spectra, QueryVariant{false, false, false, interpolation});
      engine->set_modes(engine->max_modes());
      double scale = 0;
      for (float e : map.energy)
        if (std::isfinite(e)) scale = std::max(scale, std::abs(static_cast<double>(e)));
      REQUIRE(scale > 0);
      int checked = 0, aliased = 0;
      for (int step = -6; step <= 6; step += 2) {
        const Eigen::Vector3d t = h * Eigen::Vector3d(step, -step / 2, 3 - step);
        Pose pose;
        pose.rotation = Eigen::Quaterniond(R);
        pose.translation = t;
        const QueryResult r = engine->query(pose);
        const Eigen::Vector3i idx = ((t - map.grid.origin) / h).array().round().cast<int>();
        const float e = map.energy[map.grid.index(idx.x(), idx.y(), idx.z())];
        if (r.flags & query_outside_grid) {
          CHECK(std::isnan(e));  // both agree the translation would alias
          ++aliased;
          continue;
        }
        CHECK(std::abs(e - r.energy) <= 1e-5 * scale);
        ++checked;
      }
      CHECK(checked >= 5);
      MESSAGE("rotation " << degrees << " deg: " << checked << " translations agree, " << aliased << " aliased");
    }
  }
}
