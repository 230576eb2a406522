// Full translational maps (engine/maps/full_map.h) against per-pose queries at the same
// grid translations, rotation and interpolation, on analytic Gaussian fields.
#include <cmath>
#include <doctest/doctest.h>

#include "engine/runtime/device.h"
#include "engine/maps/full_map.h"
#include "engine/query/query_engine.h"
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

TEST_CASE("full map: every inverse FFT built gives clFFT's map and a direct double-precision sum") {
  const FftLibrary fft;
  const ComputeContext ctx = make_compute_context(select_device(""));
  const double h = 0.25;
  const Eigen::Vector3d m1(0.2, -0.1, 0.3), m2(0.4, 0.3, -0.2);
  const GridSpec g1 = cube_grid(m1, 24, h), g2 = cube_grid(m2, 20, h);
  // Both parts imaginary (conjugate pairs: the half product folds), then part 2 general
  // complex (the product at k and -k).
  for (const Complex factor2 : {Complex(1, 0), Complex(0.6f, 0.8f)}) {
    std::vector<Complex> rho2 = gaussian(g2, m2, Eigen::Vector3d(3.0, 1.2, 0.7).asDiagonal());
    for (Complex& v : rho2) v *= factor2;
    const PairSpectra spectra =
        compute_pair_spectra(fft, ctx, g1, gaussian(g1, m1, Eigen::Vector3d(1.5, 1.0, 0.8).asDiagonal()), g2, rho2);
    CHECK(spectra.conjugate_pairs() == (factor2.imag() == 0 ? 1 : 0));
    const auto& d = spectra.dims;
    // Direct sum at R = I, where the rotated spectrum is sampled on nodes (no interpolation):
    // f(t_j) = sum_k S1_k S2_{-k} exp(2 pi i w_k.(c2 - c1)) dw exp(2 pi i k.j / N), in double.
    auto direct = [&](const Eigen::Vector3i& j) {
      const Eigen::Vector3d shift = spectra.part2.centre - spectra.part1.centre;
      const double dw = 1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z());
      std::complex<double> f = 0;
      for (std::size_t z = 0; z < d[2]; ++z)
        for (std::size_t y = 0; y < d[1]; ++y)
          for (std::size_t x = 0; x < d[0]; ++x) {
            const Eigen::Vector3d w(spectra.frequency(0, x), spectra.frequency(1, y), spectra.frequency(2, z));
            const std::size_t k = x + d[0] * (y + d[1] * z);
            const std::size_t minus = (d[0] - x) % d[0] + d[0] * ((d[1] - y) % d[1] + d[1] * ((d[2] - z) % d[2]));
            const double phase = 2 * M_PI *
                                 (w.dot(shift) + double(x) * j.x() / double(d[0]) + double(y) * j.y() / double(d[1]) +
                                  double(z) * j.z() / double(d[2]));
            f += std::complex<double>(spectra.part1.rho[k]) * std::complex<double>(spectra.part2.rho[minus]) * dw *
                 std::polar(1.0, phase);
          }
      return -f.real();
    };
    for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic}) {
      TranslationMapper reference(fft, ctx, spectra, interpolation, 0, MapFft::clfft);
      for (const MapFft kind : map_ffts_built()) {
        TranslationMapper mapper(fft, ctx, spectra, interpolation, 0, kind);
        CHECK(mapper.fft() == kind);
        for (const double degrees : {0.0, 35.0, 170.0}) {
          const Eigen::Matrix3d R =
              Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
          const TranslationMap want = reference.map(R), got = mapper.map(R);
          REQUIRE(got.energy.size() == want.energy.size());
          double scale = 0, worst = 0;
          std::size_t nan_mismatch = 0, finite = 0;
          for (float e : want.energy)
            if (std::isfinite(e)) scale = std::max(scale, std::abs(double(e)));
          REQUIRE(scale > 0);
          for (std::size_t i = 0; i < got.energy.size(); ++i) {
            if (std::isnan(got.energy[i]) != std::isnan(want.energy[i])) ++nan_mismatch;
            if (std::isfinite(got.energy[i]) && std::isfinite(want.energy[i])) {
              worst = std::max(worst, std::abs(double(got.energy[i]) - double(want.energy[i])));
              ++finite;
            }
          }
          INFO(map_fft_name(kind) << ", " << degrees << " deg, part 2 factor " << factor2);
          CHECK(nan_mismatch == 0);
          CHECK(finite > got.energy.size() / 20);
          CHECK(worst <= 2e-6 * scale);  // two single-precision FFTs of 48^3 points (2.3e-7 measured)
          if (degrees != 0.0) continue;
          double worst_direct = 0;
          for (const Eigen::Vector3i j : {Eigen::Vector3i(0, 0, 0), Eigen::Vector3i(1, -2, 3),
                                          Eigen::Vector3i(-4, 2, 1), Eigen::Vector3i(3, 3, -5)}) {
            const Eigen::Vector3i idx = j + (Eigen::Vector3i(int(d[0]), int(d[1]), int(d[2])) / 2);
            const float e = got.energy[got.grid.index(idx.x(), idx.y(), idx.z())];
            REQUIRE(std::isfinite(e));
            worst_direct = std::max(worst_direct, std::abs(double(e) - direct(j)));
          }
          MESSAGE(map_fft_name(kind) << ", part 2 factor " << factor2 << ": max |map - clFFT map| = " << worst / scale
                                     << " x max|E|, max |map - direct"
                                     << " double sum| = " << worst_direct / scale << " x max|E|");
          CHECK(worst_direct <= 1e-6 * scale);  // 6e-8 measured
        }
      }
    }
  }
}
