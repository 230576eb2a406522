// Conjugate-pair folding in the 6-DOF query kernel (QueryVariant::fold_conjugate_pairs,
// engine/mode_order.h): with both parts' samples imaginary (the affinity i * rho) the
// terms at w and -w are complex conjugates, so the engine evaluates each retained pair
// once with twice the weight. Checked against the same engine summing every mode, for
// m' that keep whole pairs and m' that cut one, and the sample parity that decides it.
#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <vector>

#include "engine/mode_order.h"
#include "engine/pose_query.h"
#include "engine/spectra.h"
#include "tests/stability_support.h"

namespace snapfit {
using test::pose_at;

TEST_CASE("pair folding: mode order keeps w and -w adjacent, and a prefix cuts at most one pair") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  const PairSpectra& s = pair.spectra;
  const std::vector<std::size_t> order = mode_order(s);
  REQUIRE(order.size() == s.dims[0] * s.dims[1] * s.dims[2]);
  std::vector<std::size_t> rank(order.size());
  for (std::size_t i = 0; i < order.size(); ++i) rank[order[i]] = i;
  std::size_t paired = 0, unpaired = 0, apart = 0;
  float previous = 0;
  bool increasing = true;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const std::size_t k = order[i], neg = negated_node(s.dims, k);
    const float w = float(std::hypot(s.frequency(0, k % s.dims[0]), s.frequency(1, (k / s.dims[0]) % s.dims[1]),
                                     s.frequency(2, k / (s.dims[0] * s.dims[1]))));
    increasing = increasing && w >= previous * (1 - 1e-6f);
    previous = w;
    if (neg == kNoNode || neg == k) {
      ++unpaired;
      continue;
    }
    ++paired;
    if (rank[neg] + 1 != i && rank[neg] != i + 1) ++apart;
    REQUIRE(negated_node(s.dims, neg) == k);
  }
  CHECK(increasing);
  CHECK(apart == 0);
  // Node 0 is its own partner; Nyquist components (even axes) have none.
  std::size_t nyquist = 0;
  for (std::size_t k = 0; k < order.size(); ++k) nyquist += negated_node(s.dims, k) == kNoNode;
  CHECK(unpaired == nyquist + 1);
  MESSAGE("FFT grid " << s.dims[0] << "x" << s.dims[1] << "x" << s.dims[2] << ": " << paired / 2 << " pairs, "
                      << unpaired << " single modes");
}

TEST_CASE("pair folding: folded and unfolded 6-DOF queries agree for every m', pairs cut or not") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  REQUIRE(pair.spectra.part1.sample_parity == -1);
  REQUIRE(pair.spectra.part2.sample_parity == -1);
  REQUIRE(pair.spectra.conjugate_pairs() == 1);
  for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic}) {
    QueryVariant folded, full;
    folded.interpolation = full.interpolation = interpolation;
    full.fold_conjugate_pairs = false;
    PoseQueryEngine a(test::test_context(), pair.spectra, folded, test::test_program_cache());
    PoseQueryEngine b(test::test_context(), pair.spectra, full, test::test_program_cache());
    const std::vector<Pose> poses = {pose_at({1, 0, -8}, 2, {0, 0, 1}), pose_at({0.5, 0.3, 2}, 10, {1, 1, 0}),
                                     pose_at({4, -3, 12}, 170, {0, 1, 1})};
    const std::size_t total = a.max_modes();
    for (const std::size_t m : {std::size_t(1), std::size_t(2), std::size_t(3), std::size_t(64), std::size_t(65),
                                std::size_t(4096), std::size_t(4097), total - 1, total}) {
      a.set_modes(m);
      b.set_modes(m);
      const std::vector<QueryResult> ra = a.query_batch(poses), rb = b.query_batch(poses);
      for (std::size_t n = 0; n < poses.size(); ++n) {
        CAPTURE(m);
        CAPTURE(n);
        CHECK(ra[n].modes == m);
        // Both sum the same modes in float in another order: agreement to float round-off
        // of the summed magnitudes. Im f is 0 for complete pairs; a cut pair's lone mode
        // and the Nyquist modes (no partner) give the rest, in both.
        const double e_scale = std::abs(rb[n].score) + std::abs(rb[n].energy) + 1e-3;
        const double f_scale = rb[n].force.norm() + 1e-3, t_scale = rb[n].torque.norm() + 1e-3;
        CHECK(std::abs(ra[n].energy - rb[n].energy) <= 2e-4 * e_scale);
        CHECK((ra[n].force - rb[n].force).norm() <= 2e-4 * f_scale);
        CHECK((ra[n].torque - rb[n].torque).norm() <= 2e-3 * t_scale);
        CHECK(std::abs(ra[n].score.imag() - rb[n].score.imag()) <= 2e-4 * e_scale);
      }
    }
  }
}

TEST_CASE("pair folding: sample parity is real, imaginary or general, and only real correlations fold") {
  const FftLibrary fft;
  GridSpec grid;
  grid.dims = {5, 4, 3};
  grid.spacing = 0.5;
  std::vector<Complex> real(grid.count()), imaginary(grid.count()), general(grid.count());
  for (std::size_t i = 0; i < grid.count(); ++i) {
    const float v = std::sin(0.7f * float(i)) + 0.1f;
    real[i] = Complex(v, 0);
    imaginary[i] = Complex(0, v);
    general[i] = Complex(v, 0.3f * v);
  }
  auto parities = [&](const std::vector<Complex>& a, const std::vector<Complex>& b) {
    const PairSpectra s = compute_pair_spectra(fft, test::test_context(), grid, a, grid, b, false);
    return std::array<int, 3>{s.part1.sample_parity, s.part2.sample_parity, s.conjugate_pairs()};
  };
  CHECK(parities(real, real) == std::array<int, 3>{1, 1, 1});
  CHECK(parities(imaginary, imaginary) == std::array<int, 3>{-1, -1, 1});
  // Real with imaginary: the terms at w and -w are minus each other's conjugates (f is
  // imaginary), not folded; general complex samples are not folded either.
  CHECK(parities(real, imaginary) == std::array<int, 3>{1, -1, 0});
  CHECK(parities(general, imaginary) == std::array<int, 3>{0, -1, 0});
}

}  // namespace snapfit
