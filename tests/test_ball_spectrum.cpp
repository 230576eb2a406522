// Ball spectra (engine/spectra/ball_spectrum.h): the analytic transform against a radial
// quadrature, the OpenCL direct NDFT and the type-1 NUFFT against the double-precision
// sum, and rotated ball sets (exact spectra) as the reference for the engine's
// spectrum-rotation interpolation (engine/query/reference_query.h, the queries' schemes).
#include <cmath>
#include <doctest/doctest.h>
#include <random>

#include "engine/spectra/ball_spectrum.h"
#include "engine/query/reference_query.h"
#include "tests/test_engine_support.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

using test::kPi;

std::vector<Ball> random_balls(int n, unsigned seed, double half_extent, double r_lo, double r_hi) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> pos(-half_extent, half_extent), rad(r_lo, r_hi);
  std::vector<Ball> balls;
  for (int i = 0; i < n; ++i) balls.push_back({Eigen::Vector3d(pos(rng), pos(rng), pos(rng)), rad(rng)});
  return balls;
}

double total_volume(const std::vector<Ball>& balls) {
  double v = 0;
  for (const Ball& b : balls) v += ball_transform(b.radius, 0);
  return v;
}

template <class A, class B>
double max_difference(const std::vector<A>& a, const std::vector<B>& b) {
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(std::complex<double>(a[i]) - std::complex<double>(b[i])));
  return worst;
}

FrequencyLattice lattice_for(std::array<std::size_t, 3> dims, double spacing, Eigen::Vector3d centre) {
  FrequencyLattice l;
  l.dims = dims;
  l.length = spacing * Eigen::Vector3d(double(dims[0]), double(dims[1]), double(dims[2]));
  l.centre = centre;
  return l;
}

}  // namespace

TEST_CASE("ball transform: closed form against a radial quadrature of the indicator") {
  // f^(q) = 4 pi int_0^r rho^2 sin(2 pi q rho) / (2 pi q rho) d rho, Simpson with 20000 panels.
  for (double r : {0.3, 1.0, 2.5})
    for (double q : {0.0, 1e-4, 0.01, 0.2, 0.77, 3.1}) {
      CAPTURE(r);
      CAPTURE(q);
      const int n = 20000;
      double sum = 0;
      for (int i = 0; i <= n; ++i) {
        const double rho = r * i / n, x = 2 * kPi * q * rho;
        const double f = 4 * kPi * rho * rho * (x < 1e-8 ? 1.0 : std::sin(x) / x);
        sum += f * (i == 0 || i == n ? 1 : i % 2 ? 4 : 2);
      }
      const double quadrature = sum * r / n / 3;
      CHECK(ball_transform(r, q) == doctest::Approx(quadrature).epsilon(1e-9).scale(4.0 / 3.0 * kPi * r * r * r));
    }
}

TEST_CASE("ball spectrum: the OpenCL direct NDFT matches the double sum") {
  const std::vector<Ball> balls = random_balls(300, 3, 4.0, 0.2, 1.5);
  const FrequencyLattice lattice = lattice_for({16, 12, 10}, 0.8, Eigen::Vector3d(0.1, -0.2, 0.3));
  const auto modes = lattice_modes(lattice);
  const auto reference = ball_spectrum_reference(balls, lattice, modes);
  const auto direct = ball_spectrum_direct(test::test_context(), balls, lattice, {}, test::test_program_cache());
  REQUIRE(direct.size() == lattice.count());
  CHECK(max_difference(direct, reference) <= 2e-6 * total_volume(balls));
  // A list of modes gives the same values as the whole lattice.
  const std::vector<std::array<int, 3>> some = {modes[5], modes[77], modes[1000]};
  const auto listed = ball_spectrum_direct(test::test_context(), balls, lattice, some, test::test_program_cache());
  CHECK(listed[1] == direct[77]);
  CHECK(listed[2] == direct[1000]);
}

TEST_CASE("ball spectrum: the type-1 NUFFT matches the double sum to the requested tolerance") {
  const std::vector<Ball> balls = random_balls(400, 5, 5.0, 0.15, 2.0);
  const FrequencyLattice lattice = lattice_for({24, 20, 18}, 0.7, Eigen::Vector3d(0.2, 0.1, -0.3));
  const auto reference = ball_spectrum_reference(balls, lattice, lattice_modes(lattice));
  const FftLibrary library;
  double previous = 1e300;
  for (double tolerance : {1e-2, 1e-4, 1e-5}) {
    CAPTURE(tolerance);
    BallNufftOptions options;
    options.tolerance = tolerance;
    BallNufftStats stats;
    const auto nufft = ball_spectrum_nufft(library, test::test_context(), balls, lattice, options, &stats);
    const double error = max_difference(nufft, reference) / total_volume(balls);
    MESSAGE("tolerance " << tolerance << ": error " << error << ", " << stats.radius_nodes << " radius nodes, width "
                         << stats.kernel_width);
    CHECK(error <= tolerance);
    CHECK(error < previous);
    previous = error;
    CHECK(stats.fine_dims[0] >= 48);
  }
}

TEST_CASE("ball spectrum: rotating the balls is the exact reference for the rotation interpolation") {
  const std::vector<Ball> part1 = random_balls(60, 7, 2.5, 0.5, 1.2), part2 = random_balls(40, 9, 2.0, 0.4, 1.0);
  const Pose pose{Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized())),
                  Eigen::Vector3d(0.8, -0.5, 0.3)};
  const Eigen::Matrix3d R = pose.rotation.toRotationMatrix();
  // Spectra on a lattice of `points` per axis at spacing 0.5: part 2 as it is (interpolated
  // at -R^T w by the query) or its balls turned by R (sampled at lattice nodes: exact).
  auto spectra = [&](std::size_t points, bool turned) {
    PairSpectra s;
    s.dims = {points, points, points};
    s.spacing = 0.5;
    s.length = Eigen::Vector3d::Constant(0.5 * double(points));
    std::vector<Ball> moved = part2;
    if (turned)
      for (Ball& b : moved) b.centre = R * b.centre;
    const FrequencyLattice l1 = lattice_for(s.dims, s.spacing, Eigen::Vector3d::Zero());
    const FrequencyLattice l2 = lattice_for(s.dims, s.spacing, Eigen::Vector3d::Zero());
    auto to_float = [](const std::vector<std::complex<double>>& v) { return std::vector<Complex>(v.begin(), v.end()); };
    s.part1.rho = to_float(ball_spectrum_reference(part1, l1, lattice_modes(l1)));
    s.part2.rho = to_float(ball_spectrum_reference(moved, l2, lattice_modes(l2)));
    s.part1.half_extent = Eigen::Vector3d::Constant(3.7);
    s.part2.half_extent = Eigen::Vector3d::Constant(3.0);
    s.part1.sample_parity = s.part2.sample_parity = 1;
    return s;
  };
  ReferenceOptions options;
  options.torque = false;
  Pose translated = pose;
  translated.rotation = Eigen::Quaterniond::Identity();
  double previous_cubic = 1e300;
  for (std::size_t points : {32, 48}) {
    CAPTURE(points);
    const PairSpectra plain = spectra(points, false), turned = spectra(points, true);
    const double exact = reference_query(turned, translated, options).energy;
    REQUIRE(std::abs(exact) > 0);
    options.interpolation = Interpolation::trilinear;
    const double linear = std::abs(reference_query(plain, pose, options).energy - exact) / std::abs(exact);
    options.interpolation = Interpolation::tricubic;
    const double cubic = std::abs(reference_query(plain, pose, options).energy - exact) / std::abs(exact);
    MESSAGE(points << " points: relative energy error trilinear " << linear << ", tricubic " << cubic);
    CHECK(cubic < linear);
    CHECK(cubic < previous_cubic);  // more oversampling, better interpolation
    previous_cubic = cubic;
    // At the identity both schemes sample the lattice nodes, where they are exact.
    const double at_nodes = reference_query(plain, translated, options).energy;
    options.interpolation = Interpolation::trilinear;
    CHECK(reference_query(plain, translated, options).energy == doctest::Approx(at_nodes).epsilon(1e-12));
  }
}

TEST_CASE("ball spectrum: bad input gives a clear error") {
  const FftLibrary library;
  const FrequencyLattice lattice = lattice_for({8, 8, 8}, 1.0, Eigen::Vector3d::Zero());
  const std::vector<Ball> one = {{Eigen::Vector3d::Zero(), 1.0}};
  BallNufftOptions bad;
  bad.tolerance = 0;
  CHECK(test::error_of([&] { ball_spectrum_nufft(library, test::test_context(), {}, lattice); }).find("no balls") !=
        std::string::npos);
  CHECK(test::error_of([&] {
          ball_spectrum_nufft(library, test::test_context(), one, lattice, bad);
        }).find("tolerance must be in (0, 0.1]") != std::string::npos);
  CHECK(test::error_of([&] {
          ball_spectrum_nufft(library, test::test_context(), {{Eigen::Vector3d::Zero(), -1.0}}, lattice);
        }).find("non-positive radius") != std::string::npos);
}
