// Conjugate-pair folding in the 6-DOF query kernel (QueryVariant::fold_conjugate_pairs,
// engine/spectra/mode_order.h): with both parts' samples imaginary (the affinity i * rho) the
// terms at w and -w are complex conjugates, so the engine evaluates each retained pair
// once with twice the weight. Checked against the same engine summing every mode, for
// m' that keep whole pairs and m' that cut one, and the sample parity that decides it.
#include <algorithm>
#include <cmath>
#include <complex>
#include <doctest/doctest.h>
#include <vector>

#include "engine/spectra/mode_order.h"
#include "engine/query/query_engine.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"
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
    auto a = make_query_engine(test::test_context(), pair.spectra, folded, test::test_program_cache());
    auto b = make_query_engine(test::test_context(), pair.spectra, full, test::test_program_cache());
    const std::vector<Pose> poses = {pose_at({1, 0, -8}, 2, {0, 0, 1}), pose_at({0.5, 0.3, 2}, 10, {1, 1, 0}),
                                     pose_at({4, -3, 12}, 170, {0, 1, 1})};
    const std::size_t total = a->max_modes();
    for (const std::size_t m : {std::size_t(1), std::size_t(2), std::size_t(3), std::size_t(64), std::size_t(65),
                                std::size_t(4096), std::size_t(4097), total - 1, total}) {
      a->set_modes(m);
      b->set_modes(m);
      const std::vector<QueryResult> ra = a->query_batch(poses), rb = b->query_batch(poses);
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
        // The torque is the interpolant's rotational slope. Catmull-Rom's is continuous;
        // the trilinear one jumps at the nodes, where rotated frequencies of these poses
        // sit on some axes, and a node's slope is taken from one side: at -w' from the
        // other than at w', so folded and unfolded legitimately differ there.
        if (interpolation == Interpolation::tricubic) CHECK((ra[n].torque - rb[n].torque).norm() <= 2e-3 * t_scale);
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
    const PairSpectra s = compute_pair_spectra(fft, test::test_context(), grid, a, grid, b);
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

namespace snapfit {

TEST_CASE("pair folding: translation-only folded, unfolded and 6-DOF at R = I agree for every m'") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  REQUIRE(pair.spectra.conjugate_pairs() == 1);
  QueryVariant folded, full, six;
  folded.translation_only = full.translation_only = true;
  folded.torque = full.torque = six.torque = false;
  full.fold_conjugate_pairs = false;
  six.interpolation = Interpolation::trilinear;
  auto a = make_query_engine(test::test_context(), pair.spectra, folded, test::test_program_cache());
  auto b = make_query_engine(test::test_context(), pair.spectra, full, test::test_program_cache());
  auto c = make_query_engine(test::test_context(), pair.spectra, six, test::test_program_cache());
  const std::vector<Pose> poses = {test::pose_at({1, 0, -8}), test::pose_at({0.5, 0.3, 2}), test::pose_at({2, -1, -4})};
  const std::size_t total = a->max_modes();
  const std::vector<std::size_t> ladder = {1, 2, 3, 64, 65, 4096, 4097, total / 2, total - 1, total};
  // Scales: the largest |f| and |F| of the unfolded sum over every m' and pose (the
  // sums cancel at some poses, so their own size is not the float round-off's scale).
  double e_scale = 0, f_scale = 0;
  for (const std::size_t m : ladder) {
    b->set_modes(m);
    for (const Pose& p : poses) {
      const QueryResult r = b->query(p);
      e_scale = std::max(e_scale, std::abs(r.score));
      f_scale = std::max(f_scale, r.force.norm());
    }
  }
  std::size_t folded_at = 0, unfolded_at = 0;
  for (const std::size_t m : ladder) {
    a->set_modes(m);
    b->set_modes(m);
    c->set_modes(m);
    // Folded runs evaluate about half the terms (one per pair, plus single terms for a
    // cut pair and nodes without a partner, which outnumber the savings only at m' < 4);
    // past the first unpartnered node of a skipped line (the Nyquist planes, at about
    // half of all modes) it sums every line.
    if (m >= 64 && a->evaluated_terms() < m) ++folded_at;
    if (m >= 64 && a->evaluated_terms() == m) ++unfolded_at;
    CHECK(b->evaluated_terms() == m);
    for (const Pose& p : poses) {
      CAPTURE(m);
      const QueryResult ra = a->query(p), rb = b->query(p), rc = c->query(p);
      REQUIRE(ra.flags == query_ok);
      CHECK(std::abs(ra.energy - rb.energy) <= 2e-5 * e_scale);
      CHECK(std::abs(ra.score.imag() - rb.score.imag()) <= 2e-5 * e_scale);
      CHECK((ra.force - rb.force).norm() <= 2e-5 * f_scale);
      // And the 6-DOF kernel at R = I (its interpolation at lattice points is exact).
      CHECK(std::abs(ra.energy - rc.energy) <= 2e-5 * e_scale);
      CHECK((ra.force - rc.force).norm() <= 2e-5 * f_scale);
    }
  }
  CHECK(folded_at >= 5);    // every m' from 64 to half of the modes folds
  CHECK(unfolded_at >= 2);  // total - 1 and total reach the Nyquist planes
}

}  // namespace snapfit
