// The host double-precision reference (engine/query/reference_query.h): exact (up to the float
// spectra's round-off) against a brute-force physical-domain sum where rotated samples
// land on the grid (lattice rotations), and the device kernel's float result against
// it at the same m'.
#include <doctest/doctest.h>
#include <random>

#include "engine/spectra/fft3d.h"
#include "engine/query/query_engine.h"
#include "engine/query/reference_query.h"
#include "tests/test_engine_support.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

GridSpec grid(Eigen::Vector3i dims) {
  GridSpec g;
  g.dims = dims;
  g.spacing = 1.0;
  g.origin = -0.5 * (dims.cast<double>() - Vector3d::Ones());  // symmetric about 0
  return g;
}

std::vector<Complex> random_field(const GridSpec& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n;
  std::vector<Complex> f(g.count());
  for (Complex& v : f) v = Complex(n(rng), n(rng));
  return f;
}

// f(R, t) = sum over part 1's samples x of rho1(x) rho2(R^T (x - t)) h^3, counting only
// the x whose R^T (x - t) is one of part 2's samples (exact for lattice rotations).
// `magnitude` receives the sum of |terms|, the scale of round-off.
std::complex<double> brute_force(const GridSpec& g1, const std::vector<Complex>& r1, const GridSpec& g2,
                                 const std::vector<Complex>& r2, const Eigen::Matrix3d& R, const Vector3d& t,
                                 double& magnitude) {
  std::complex<double> sum = 0;
  magnitude = 0;
  for (int k = 0; k < g1.dims.z(); ++k)
    for (int j = 0; j < g1.dims.y(); ++j)
      for (int i = 0; i < g1.dims.x(); ++i) {
        const Vector3d p = R.transpose() * (g1.point(i, j, k) - t);
        const Vector3d u = (p - g2.origin) / g2.spacing;
        const Eigen::Vector3i n = u.array().round().cast<int>();
        if ((u - n.cast<double>()).norm() > 1e-9) continue;
        if ((n.array() < 0).any() || (n.array() >= g2.dims.array()).any()) continue;
        const std::complex<double> term =
            std::complex<double>(r1[g1.index(i, j, k)]) * std::complex<double>(r2[g2.index(n.x(), n.y(), n.z())]);
        sum += term;
        magnitude += std::abs(term);
      }
  magnitude *= std::pow(g1.spacing, 3);
  return sum * std::pow(g1.spacing, 3);
}

}  // namespace

TEST_CASE("reference query: all modes equal a brute-force physical-domain sum under a lattice rotation") {
  const GridSpec g1 = grid({10, 10, 8}), g2 = grid({6, 6, 5});
  const auto r1 = random_field(g1, 1), r2 = random_field(g2, 2);
  const FftLibrary fft;
  const PairSpectra s = compute_pair_spectra(fft, test::test_context(), g1, r1, g2, r2);
  REQUIRE(s.dims[0] == s.dims[1]);  // so a quarter turn about z maps nodes onto nodes
  struct Case {
    Eigen::Matrix3d R;
    Vector3d t;
  };
  const Eigen::Matrix3d quarter = Eigen::AngleAxisd(M_PI / 2, Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d half_x = Eigen::AngleAxisd(M_PI, Vector3d::UnitX()).toRotationMatrix();
  const Case cases[] = {{Eigen::Matrix3d::Identity(), {1, -2, 0.5}},
                        {quarter, {1, -2, 0.5}},
                        {quarter * quarter, {-2, 0, 1.5}},
                        {half_x, {0, 1, -0.5}}};
  for (const Case& c : cases) {
    Pose pose;
    pose.rotation = Eigen::Quaterniond(c.R);
    pose.translation = c.t;
    double magnitude = 0;
    const std::complex<double> expected = brute_force(g1, r1, g2, r2, c.R, c.t, magnitude);
    REQUIRE(magnitude > 0);
    for (Interpolation scheme : {Interpolation::trilinear, Interpolation::tricubic}) {
      ReferenceOptions options;
      options.interpolation = scheme;
      const QueryResult r = reference_query(s, pose, options);
      CAPTURE(c.t.transpose());
      REQUIRE(r.flags == query_ok);
      // The spectra are float (clFFT): exact up to their round-off, ~1e-7 of the terms.
      CHECK(std::abs(r.score - expected) < 1e-6 * magnitude);
      CHECK(std::abs(r.energy + expected.real()) < 1e-6 * magnitude);
    }
  }
}

TEST_CASE("reference query: the device kernel's float sums agree with double accumulation") {
  const GridSpec g1 = grid({12, 10, 9}), g2 = grid({7, 6, 6});
  const auto r1 = random_field(g1, 3), r2 = random_field(g2, 4);
  const FftLibrary fft;
  const PairSpectra s = compute_pair_spectra(fft, test::test_context(), g1, r1, g2, r2);
  auto engine = make_query_engine(test::test_context(), s, QueryVariant{true, true, false, Interpolation::tricubic},
                                  test::test_program_cache());
  const std::vector<std::size_t> order = mode_order(s);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (std::size_t modes : {std::size_t(64), std::size_t(1000), engine->max_modes()}) {
    engine->set_modes(modes);
    for (int i = 0; i < 3; ++i) {
      Pose pose;
      pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(3 * u(rng), Vector3d(u(rng), u(rng), u(rng)).normalized()));
      pose.translation = Vector3d(u(rng), u(rng), u(rng));
      ReferenceOptions options;
      options.modes = modes;
      const QueryResult ref = reference_query(s, pose, options, &order);
      const QueryResult dev = engine->query(pose);
      CAPTURE(modes);
      REQUIRE(dev.flags == query_ok);
      // Float spectra products and sums: relative to the size of the terms summed.
      const double scale = std::abs(ref.score) + 1e-3 * std::sqrt(double(modes));
      CHECK(std::abs(dev.score - ref.score) < 1e-4 * scale);
      CHECK((dev.force - ref.force).norm() < 1e-4 * (ref.force.norm() + scale));
      CHECK((dev.torque - ref.torque).norm() < 1e-4 * (ref.torque.norm() + scale));
    }
  }
}
