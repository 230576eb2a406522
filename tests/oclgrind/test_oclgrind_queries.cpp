// The spectra (clFFT), the query kernels (kernels/pose_query.cl: pose_query,
// translation_lines, rotated_lines; kernels/rotated_product.cl) in every variant and in
// GPU-shaped launches, and the full map (kernels/full_map.cl with clFFT's inverse), on
// Oclgrind with its checks on and on PoCL from the same spectra: no report, and the same
// results within float rounding (docs/portability.md).
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <limits>

#include "engine/spectra/ball_spectrum.h"
#include "engine/maps/full_map.h"
#include "tests/oclgrind/oclgrind_cases.h"
#include "tests/oclgrind/oclgrind_support.h"
#include "tests/test_engine_support.h"

namespace snapfit::test {
namespace {

const double kEps = std::numeric_limits<float>::epsilon();

// E, F and T of every pose from both devices. A result is a float sum of m' <= 600 terms
// whose work-groups split it differently on the two devices (and whose exp, cospi and
// sinpi may differ by ulps): within 32 float roundings of the largest magnitude of that
// output over the poses (measured: at most 2.4e-7 of it, about 2 roundings).
void compare_results(const std::vector<QueryResult>& pocl, const std::vector<QueryResult>& oclgrind,
                     const QueryVariant& variant, const std::string& what) {
  REQUIRE(pocl.size() == oclgrind.size());
  double scale_e = 0, scale_f = 0, scale_t = 0, de = 0, df = 0, dt = 0;
  for (std::size_t i = 0; i < pocl.size(); ++i) {
    CHECK(pocl[i].flags == query_ok);
    CHECK(oclgrind[i].flags == query_ok);
    scale_e = std::max(scale_e, std::abs(pocl[i].energy));
    scale_f = std::max(scale_f, pocl[i].force.norm());
    scale_t = std::max(scale_t, pocl[i].torque.norm());
    de = std::max(de, std::abs(pocl[i].energy - oclgrind[i].energy));
    df = std::max(df, (pocl[i].force - oclgrind[i].force).norm());
    dt = std::max(dt, (pocl[i].torque - oclgrind[i].torque).norm());
  }
  MESSAGE(what << ": PoCL - Oclgrind: E " << de << " of " << scale_e << ", F " << df << " of " << scale_f << ", T "
               << dt << " of " << scale_t);
  // The poses touch: every output the variant computes is exercised.
  CHECK(scale_e > 0);
  CHECK((scale_f > 0) == variant.force);
  CHECK((scale_t > 0) == variant.torque);
  const double roundings = 32 * kEps;
  CHECK_MESSAGE(de <= roundings * scale_e, what << ": energies differ by " << de);
  CHECK_MESSAGE(df <= roundings * scale_f, what << ": forces differ by " << df);
  CHECK_MESSAGE(dt <= roundings * scale_t, what << ": torques differ by " << dt);
}

void run_query_cases(const std::vector<std::string>& kernels, const std::vector<LaunchShape>& shapes) {
  const PairSpectra& spectra = pocl_pair_spectra();
  for (const QueryCase& c : query_cases()) {
    if (c.kernels != kernels) continue;
    for (const LaunchShape& shape : shapes) {
      const std::string what = c.name + ", " + shape.name;
      OclgrindSession session(checks_for(c.kernels));
      const std::vector<QueryResult> oclgrind = run_query_case(session.context(), spectra, c, shape);
      expect_clean(session, what);
      compare_results(run_query_case(test_context(), spectra, c, shape), oclgrind, c.variant, what);
    }
  }
}

std::vector<LaunchShape> own_shape() { return {query_launch_shapes().front()}; }

}  // namespace

TEST_CASE("oclgrind: 6-DOF pose queries, every interpolation, output and folding: clean, and equal to PoCL") {
  run_query_cases({"pose_query"}, own_shape());
}

TEST_CASE("oclgrind: translation-only lines and the exact-rotation product and lines: clean, and equal to PoCL") {
  run_query_cases({"translation_lines"}, own_shape());
  run_query_cases({"rotated_product", "rotated_lines"}, own_shape());
}

TEST_CASE("oclgrind: query kernels in GPU-shaped launches (many groups, wide and single-item groups)") {
  // Each shape on Oclgrind against PoCL in its own shape: the launch shape must not
  // change the sums beyond their order.
  std::vector<LaunchShape> shapes = query_launch_shapes();
  const LaunchShape own = shapes.front();
  shapes.erase(shapes.begin());
  const PairSpectra& spectra = pocl_pair_spectra();
  for (const QueryCase& c : query_cases()) {
    // One variant of each kernel: the widest of each (tricubic with torque, forces, folded).
    const bool widest = c.variant.force && c.variant.fold_conjugate_pairs && !c.variant.half_cube &&
                        (c.variant.translation_only || c.variant.rotation == RotationMethod::exact_product ||
                         (c.variant.torque && c.variant.interpolation == Interpolation::tricubic));
    if (!widest) continue;
    const std::vector<QueryResult> pocl = run_query_case(test_context(), spectra, c, own);
    for (const LaunchShape& shape : shapes) {
      const std::string what = c.name + ", " + shape.name;
      OclgrindSession session(checks_for(c.kernels));
      const std::vector<QueryResult> oclgrind = run_query_case(session.context(), spectra, c, shape);
      expect_clean(session, what);
      compare_results(pocl, oclgrind, c.variant, what);
    }
  }
}

TEST_CASE("oclgrind: spectra (clFFT forward transforms, deconvolution) and full maps: clean, and equal to PoCL") {
  const PairSpectra& pocl = pocl_pair_spectra();
  // The sessions before the FFT library: clFFT's teardown releases what it built for them.
  OclgrindSession spectra_session(checks_for({"fft_fwd"}));
  OclgrindSession map_session(checks_for({"spectrum_product", "fft_back"}));
  const FftLibrary fft;
  {
    // The fields come from PoCL: only the transforms run on Oclgrind.
    const PairSpectra oclgrind =
        compute_pair_spectra(fft, spectra_session.context(), pocl_pair_fields().first, pocl_pair_fields().second);
    expect_clean(spectra_session, "spectra");
    REQUIRE(oclgrind.dims == pocl.dims);
    // An FFT of n points rounds each output O(log2 n) times, each time within a float
    // ulp of the largest |S| (Parseval bounds every partial sum by it, up to sqrt(n)).
    auto compare = [&](const std::vector<Complex>& a, const std::vector<Complex>& b, const std::string& what) {
      REQUIRE(a.size() == b.size());
      double scale = 0, diff = 0;
      for (std::size_t i = 0; i < a.size(); ++i) {
        scale = std::max(scale, double(std::abs(a[i])));
        diff = std::max(diff, double(std::abs(a[i] - b[i])));
      }
      MESSAGE(what << ": PoCL - Oclgrind " << diff << " of " << scale);
      CHECK(scale > 0);
      CHECK_MESSAGE(diff <= 64 * kEps * scale, what << " differ by " << diff);
    };
    compare(pocl.part1.rho, oclgrind.part1.rho, "part 1 spectrum");
    compare(pocl.part2.rho, oclgrind.part2.rho, "part 2 spectrum");
    compare(pocl.part2.deconvolved, oclgrind.part2.deconvolved, "part 2 deconvolved spectrum");
  }
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  // clFFT's path at both interpolations and low-passes; the half-spectrum product of
  // FFTW's path (kernels/full_map.cl spectrum_product_half) and VkFFT's inverse once each,
  // when built.
  struct MapCase {
    Interpolation interpolation;
    std::size_t modes;
    MapFft fft;
  };
  std::vector<MapCase> cases;
  for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic})
    for (const std::size_t modes : {std::size_t(0), std::size_t(500)})
      cases.push_back({interpolation, modes, MapFft::clfft});
  for (const MapFft fft : map_ffts_built())
    if (fft != MapFft::clfft) cases.push_back({Interpolation::trilinear, 0, fft});
  for (const MapCase& c : cases) {
    const Interpolation interpolation = c.interpolation;
    const std::size_t modes = c.modes;
    const std::string what = std::string("full map, ") + map_fft_name(c.fft) + ", " +
                             (interpolation == Interpolation::tricubic ? "tricubic" : "trilinear") +
                             (modes ? ", 500 modes" : ", every mode");
    const TranslationMap oclgrind =
        TranslationMapper(fft, map_session.context(), pocl, interpolation, modes, c.fft, test_program_cache()).map(R);
    expect_clean(map_session, what);
    const TranslationMap map =
        TranslationMapper(fft, test_context(), pocl, interpolation, modes, c.fft, test_program_cache()).map(R);
    REQUIRE(map.energy.size() == oclgrind.energy.size());
    double scale = 0, diff = 0;
    for (std::size_t i = 0; i < map.energy.size(); ++i) {
      CHECK(std::isnan(map.energy[i]) == std::isnan(oclgrind.energy[i]));
      if (std::isnan(map.energy[i])) continue;
      scale = std::max(scale, double(std::abs(map.energy[i])));
      diff = std::max(diff, double(std::abs(map.energy[i] - oclgrind.energy[i])));
    }
    MESSAGE(what << ": PoCL - Oclgrind " << diff << " of " << scale);
    CHECK(scale > 0);
    CHECK_MESSAGE(diff <= 32 * kEps * scale, what << ": energies differ by " << diff);
  }
}

TEST_CASE("oclgrind: the ball NDFT (spectra from spheres): clean, and equal to PoCL") {
  std::vector<Ball> balls;
  for (int j = 0; j < 24; ++j)
    balls.push_back({Eigen::Vector3d(std::sin(1.3 * j), std::cos(0.7 * j), 0.1 * j - 1.2), 0.2 + 0.03 * j});
  FrequencyLattice lattice;
  lattice.dims = {6, 5, 4};  // 120 modes: two 64-item groups, the second half past the end
  lattice.length = Eigen::Vector3d(4.0, 3.5, 3.0);
  lattice.centre = Eigen::Vector3d(0.1, 0.0, -0.2);
  const auto pocl = ball_spectrum_direct(test_context(), balls, lattice, {}, test_program_cache());
  OclgrindSession session(checks_for({"ball_ndft"}));
  const auto oclgrind = ball_spectrum_direct(session.context(), balls, lattice, {}, test_program_cache());
  expect_clean(session, "ball_ndft");
  REQUIRE(oclgrind.size() == pocl.size());
  // Each mode is a float sum of 24 terms bounded by the balls' volumes, in the same order
  // on both devices (sincos may differ by ulps).
  double volume = 0, diff = 0;
  for (const Ball& b : balls) volume += ball_transform(b.radius, 0);
  for (std::size_t k = 0; k < pocl.size(); ++k) diff = std::max(diff, double(std::abs(pocl[k] - oclgrind[k])));
  MESSAGE("ball_ndft: PoCL - Oclgrind " << diff << " of " << volume);
  CHECK(diff <= 32 * kEps * volume);
}

}  // namespace snapfit::test
