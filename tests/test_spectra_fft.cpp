// engine/spectra/spectra.h's two forward FFTs (FFTW on the host, clFFT on the device):
// every stored spectrum, part 2's deconvolved one too, agrees between them to single
// precision's round-off, and both give the spectrum's double-precision DTFT sum.
#include <cmath>
#include <complex>
#include <doctest/doctest.h>
#include <random>

#include "engine/spectra/spectra.h"
#include "tests/test_engine_support.h"

using namespace snapfit;

namespace {

std::vector<Complex> random_field(const GridSpec& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0, 1);
  std::vector<Complex> v(g.count());
  for (Complex& c : v) c = Complex(0, n(rng));  // imaginary, as an affinity
  return v;
}

// S(w) = h^3 sum_j c_j exp(-2 pi i w.(x_j - c)) in double.
std::complex<double> dtft(const GridSpec& g, const std::vector<Complex>& c, const Eigen::Vector3d& centre,
                          const Eigen::Vector3d& w) {
  std::complex<double> s = 0;
  for (std::size_t j = 0; j < g.count(); ++j)
    s += std::complex<double>(c[j]) * std::exp(std::complex<double>(0, -2 * M_PI * w.dot(g.point(j) - centre)));
  return s * std::pow(g.spacing, 3);
}

double largest(const std::vector<Complex>& v) {
  double m = 0;
  for (const Complex& c : v) m = std::max(m, double(std::abs(c)));
  return m;
}

double largest_difference(const std::vector<Complex>& a, const std::vector<Complex>& b) {
  REQUIRE(a.size() == b.size());
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, double(std::abs(a[i] - b[i])));
  return m;
}

}  // namespace

TEST_CASE("spectra: the host FFT and the device FFT give the same spectra, both the DTFT sum") {
  const GridSpec g1 = test::grid_spec({11, 9, 8}, 0.5, {-2.0, -1.7, -1.4}),
                 g2 = test::grid_spec({6, 7, 5}, 0.5, {0.3, -1.1, 0.2});
  const auto c1 = random_field(g1, 3), c2 = random_field(g2, 4);
  const FftLibrary library;
  SpectrumOptions device_options, host_options;
  device_options.fft = FftPlace::device;
  host_options.fft = FftPlace::host;
  const PairSpectra device = compute_pair_spectra(library, test::test_context(), g1, c1, g2, c2, device_options);
  PairSpectra host;
  try {
    host = compute_pair_spectra(library, test::test_context(), g1, c1, g2, c2, host_options);
  } catch (const Error& e) {
    MESSAGE("no host FFT in this build: " << e.what());
    CHECK(std::string(e.what()).find("FFTW") != std::string::npos);
    return;
  }
  REQUIRE(host.dims == device.dims);
  REQUIRE(!host.part2.deconvolved.empty());
  const double r1 = largest_difference(host.part1.rho, device.part1.rho) / largest(device.part1.rho);
  const double r2 = largest_difference(host.part2.rho, device.part2.rho) / largest(device.part2.rho);
  const double rd =
      largest_difference(host.part2.deconvolved, device.part2.deconvolved) / largest(device.part2.deconvolved);
  MESSAGE("largest difference host - device over the largest |S|: part 1 " << r1 << ", part 2 " << r2
                                                                          << ", deconvolved " << rd);
  CHECK(r1 < 1e-5);
  CHECK(r2 < 1e-5);
  CHECK(rd < 1e-5);

  const auto& d = host.dims;
  for (std::size_t k : {std::size_t(0), std::size_t(5), std::size_t(123), std::size_t(d[0] * d[1] * d[2] - 7)}) {
    const Eigen::Vector3d w(signed_index(k % d[0], d[0]) / host.length.x(),
                            signed_index((k / d[0]) % d[1], d[1]) / host.length.y(),
                            signed_index(k / (d[0] * d[1]), d[2]) / host.length.z());
    for (const PairSpectra* s : {static_cast<const PairSpectra*>(&host), &device}) {
      const std::complex<double> s1 = dtft(g1, c1, s->part1.centre, w), s2 = dtft(g2, c2, s->part2.centre, w);
      CHECK(std::abs(s1 - std::complex<double>(s->part1.rho[k])) < 1e-5 * largest(s->part1.rho));
      CHECK(std::abs(s2 - std::complex<double>(s->part2.rho[k])) < 1e-5 * largest(s->part2.rho));
    }
  }
}
