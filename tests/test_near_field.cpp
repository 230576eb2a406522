// The near-far split (engine/query/near_field.h, engine/query/split_query.h):
// - the near part summed in space equals the all-mode exact-rotation sum of part 1's
//   spectrum times (1 - G) with part 2's, at off-lattice poses (E, F and T);
// - far part plus near part at every mode is the exact sum over every mode;
// - the far part's spectrum is part 1's times G;
// - the background near part, at a held pose, ends at the each-query values; before the
//   worker's first one the far part alone is returned with an estimate as large as it;
// - a split without a near field is refused with a message that says so.
#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <doctest/doctest.h>
#include <random>
#include <thread>
#include <vector>

#include "engine/query/near_field.h"
#include "engine/query/query_engine.h"
#include "engine/spectra/spectra.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/trajectory.h"
#include "snapfit/error.h"
#include "tests/stability_support.h"

namespace snapfit {
namespace {

using Eigen::Vector3d;

// Imaginary samples (the affinity i * rho is): a smooth bump plus noise, so the residual
// of its smoothing is neither zero nor everything.
std::vector<Complex> samples(const GridSpec& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0, 0.3f);
  std::vector<Complex> v(g.count());
  const Vector3d centre = g.origin + 0.5 * g.spacing * (g.dims - Eigen::Vector3i::Ones()).cast<double>();
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = Complex(0, float(std::exp(-(g.point(i) - centre).squaredNorm() / 2.0)) + n(rng));
  return v;
}

QueryVariant exact_each_query() {
  QueryVariant v;
  v.rotation = RotationMethod::exact_product;
  v.product_update = ProductUpdate::each_query;
  return v;
}

Pose pose_of(double angle, const Vector3d& axis, const Vector3d& t) {
  Pose p;
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized()));
  p.translation = t;
  return p;
}

struct SmallPair {
  GridSpec g1 = test::grid_spec({10, 9, 8}, 0.5, {-2.2, -2.0, -1.7}),
           g2 = test::grid_spec({6, 7, 5}, 0.5, {-1.3, -1.4, -1.1});
  std::vector<Complex> rho1 = samples(g1, 21), rho2 = samples(g2, 22);
  PairSpectra spectra;
  SmallPair() {
    const FftLibrary fft;
    spectra = compute_pair_spectra(fft, test::test_context(), g1, rho1, g2, rho2);
  }
};

}  // namespace

TEST_CASE("near field: the near part in space is the all-mode exact sum over part 1's spectrum times (1 - G)") {
  SmallPair p;
  REQUIRE(p.spectra.part2.deconvolved_width > 0);
  NearFieldOptions options;
  options.width_spacings = 1.5;
  options.kernel_width = 7;
  options.margin_widths = 100;  // the whole periodic box: no sample of part 2 left out
  const FftLibrary fft;
  const NearField near = build_near_field(fft, test::test_context(), p.spectra, p.g2, p.rho2, options);
  CHECK(near.periodic);
  CHECK(near.samples.size() == p.rho2.size());

  // The reference: the engine's every-mode exact sum with part 1's spectrum times (1 - G).
  PairSpectra residual = p.spectra;
  const PairSpectra far = far_spectra(p.spectra, near);
  for (std::size_t k = 0; k < residual.part1.rho.size(); ++k) residual.part1.rho[k] -= far.part1.rho[k];
  auto engine = make_query_engine(test::test_context(), residual, exact_each_query(), test::test_program_cache());
  engine->set_modes(engine->max_modes());
  for (const Pose& pose : {pose_of(0.37, {1, 2, 3}, {0.2, -0.1, 0.3}), pose_of(2.2, {-1, 0.5, 0.2}, {-0.4, 0.25, 0.1}),
                           pose_of(1e-3, {0, 0, 1}, {0.05, 0.0, -0.3})}) {
    const QueryResult ref = engine->query(pose);
    REQUIRE(ref.flags == query_ok);
    const NearWrench n = near_wrench(near, pose);
    CAPTURE(ref.energy);
    CAPTURE(n.energy);
    CHECK(std::abs(n.energy - ref.energy) <= 2e-4 * std::abs(ref.energy));
    CHECK((n.force - ref.force).norm() <= 2e-3 * ref.force.norm());
    CHECK((n.torque - ref.torque).norm() <= 2e-3 * ref.torque.norm());
  }
}

// Part 2's grid box at `pose`, in part 1's frame: where its samples are.
Eigen::AlignedBox3d part2_box_at(const GridSpec& g2, const Pose& pose) {
  Eigen::AlignedBox3d box;
  const Vector3d size = g2.spacing * (g2.dims - Eigen::Vector3i::Ones()).cast<double>();
  for (int c = 0; c < 8; ++c) {
    const Vector3d corner = g2.origin + Vector3d((c & 1) * size.x(), ((c >> 1) & 1) * size.y(), (c >> 2) * size.z());
    box.extend(pose.rotation * corner + pose.translation);
  }
  return box;
}

TEST_CASE("near field: what the kept nodes leave out is within its bound, and where part 2 can reach nothing is") {
  SmallPair p;
  const FftLibrary fft;
  NearFieldOptions options;
  options.width_spacings = 1.5;
  options.kernel_width = 5;
  options.margin_widths = 100;  // the whole periodic box: the near part with nothing left out
  const NearField whole = build_near_field(fft, test::test_context(), p.spectra, p.g2, p.rho2, options);
  REQUIRE(whole.periodic);
  options.margin_widths = 0.5;  // part 1's samples and a little beyond
  const NearField tight = build_near_field(fft, test::test_context(), p.spectra, p.g2, p.rho2, options);
  REQUIRE_FALSE(tight.wraps[0]);
  CHECK(tight.edge_value > 0);
  CHECK(tight.edge_gradient > 0);

  // Part 2 partly beyond part 1's samples, turned off the lattice: its taps there read the
  // residual's ringing, which the tight field leaves out and bounds.
  for (const Pose& pose : {pose_of(0.37, {1, 2, 3}, {3.4, -0.1, 0.3}), pose_of(2.2, {-1, 0.5, 0.2}, {-0.4, 3.2, 0.1}),
                           pose_of(0.8, {0, 1, 1}, {2.9, 2.7, -2.5}), pose_of(1e-3, {0, 0, 1}, {0.05, 0.0, -3.3})}) {
    CAPTURE(pose.translation.transpose());
    const NearWrench all = near_wrench(whole, pose), cut = near_wrench(tight, pose);
    CHECK(all.left_out.energy == 0);
    CHECK(all.left_out.torque == 0);
    CHECK(cut.left_out.energy > 0);
    CHECK(std::abs(cut.energy - all.energy) <= cut.left_out.energy);
    CHECK((cut.force - all.force).norm() <= cut.left_out.force);
    CHECK((cut.torque - all.torque).norm() <= cut.left_out.torque);

    // Kept where part 2 is at this pose (its reach): nothing left out, the whole-box values.
    NearFieldOptions reaching = options;
    reaching.reach = part2_box_at(p.g2, pose);
    const NearField covering = build_near_field(fft, test::test_context(), p.spectra, p.g2, p.rho2, reaching);
    const NearWrench n = near_wrench(covering, pose);
    CHECK(n.left_out.energy == 0);
    CHECK(n.left_out.force == 0);
    CHECK(std::abs(n.energy - all.energy) <= 1e-5 * std::abs(all.energy));
    CHECK((n.force - all.force).norm() <= 1e-5 * all.force.norm());
    CHECK((n.torque - all.torque).norm() <= 1e-5 * all.torque.norm());
  }
}

TEST_CASE("near field: a scene's pair keeps the nodes part 2 can reach along its trajectory, and bounds the rest") {
  const Scene scene = test::small_peg_hole_scene();
  REQUIRE_FALSE(scene.trajectory.keyframes.empty());
  const AssemblyPair pair = test::build_small_pair(scene, 2, true);
  REQUIRE(pair.spectra.near);
  REQUIRE(pair.region.box_known);
  const NearField& near = *pair.spectra.near;
  const auto& keys = scene.trajectory.keyframes;
  for (int i = 0; i <= 20; ++i) {
    const Pose pose = trajectory_pose(scene.trajectory, keys.front().time_s +
                                                            (keys.back().time_s - keys.front().time_s) * i / 20.0);
    CAPTURE(i);
    const NearWrench n = near_wrench(near, pose);
    CHECK(n.samples == near.samples.size());
    CHECK(n.left_out.energy == 0);
  }
  // Far off to the side, beyond the region and the nodes kept: left out, and bounded.
  Pose aside = keys.back().pose;
  aside.translation += pair.region.box.sizes().cwiseProduct(Vector3d(1.5, 0, 0));
  const NearWrench n = near_wrench(near, aside);
  CHECK(n.samples < near.samples.size());
  CHECK(n.left_out.energy > 0);
  CHECK(n.left_out.force > 0);
  CHECK(n.left_out.torque > 0);
}

TEST_CASE("near field: kept whole along one axis only, the taps wrap along it and not along the others") {
  SmallPair p;
  const FftLibrary fft;
  NearFieldOptions options;
  options.width_spacings = 1.5;
  options.kernel_width = 7;
  options.margin_widths = 100;
  const NearField whole = build_near_field(fft, test::test_context(), p.spectra, p.g2, p.rho2, options);
  // Part 2 straddling the box's period along z (its edge at c1 +- L_z / 2).
  const Pose pose = pose_of(0.4, {1, -1, 2}, {0.3, -0.2, 0.5 * p.spectra.length.z()});
  Eigen::AlignedBox3d reach = part2_box_at(p.g2, pose);
  reach.min().z() -= 10 * p.spectra.length.z();
  reach.max().z() += 10 * p.spectra.length.z();
  options.reach = reach;
  const NearField slab = build_near_field(fft, test::test_context(), p.spectra, p.g2, p.rho2, options);
  CHECK(slab.wraps[2]);
  CHECK_FALSE(slab.wraps[0]);
  CHECK_FALSE(slab.periodic);
  const NearWrench all = near_wrench(whole, pose), n = near_wrench(slab, pose);
  CHECK(n.left_out.energy == 0);
  CHECK(std::abs(n.energy - all.energy) <= 1e-5 * std::abs(all.energy));
  CHECK((n.force - all.force).norm() <= 1e-5 * all.force.norm());
  CHECK((n.torque - all.torque).norm() <= 1e-5 * all.torque.norm());
}

TEST_CASE("near field: the far part is part 1's spectrum times G, and far plus near at every mode is the exact sum") {
  const AssemblyPair pair = [] {
    const FftLibrary fft;
    PairOptions options;
    options.use_cache = false;
    options.note = [](const std::string&) {};
    options.descriptors.program_cache = test::test_program_cache();
    options.near_field = true;
    options.near.margin_widths = 100;  // the whole box and a tight kernel, for the identity
    options.near.reach = Eigen::AlignedBox3d(Vector3d::Constant(-1e3), Vector3d::Constant(1e3));
    options.near.kernel_width = 7;
    return build_assembly_pair(test::small_peg_hole_scene(), test::test_context(), fft, options);
  }();
  REQUIRE(pair.spectra.near);
  const NearField& near = *pair.spectra.near;
  const PairSpectra& s = pair.spectra;
  // G at a few modes.
  for (std::size_t k : {std::size_t(0), std::size_t(5), std::size_t(s.dims[0] * 3 + 2)}) {
    double w2 = 0;
    std::size_t rest = k;
    for (int a = 0; a < 3; ++a) {
      const double w = s.frequency(a, rest % s.dims[a]);
      w2 += w * w;
      rest /= s.dims[a];
    }
    const std::complex<double> expected =
        std::complex<double>(s.part1.rho[k]) * std::exp(-2 * M_PI * M_PI * near.width * near.width * w2);
    CHECK(std::abs(std::complex<double>(near.far_rho1[k]) - expected) <= 1e-6 * std::abs(s.part1.rho[k]) + 1e-12);
  }

  auto whole = make_query_engine(test::test_context(), s, exact_each_query(), test::test_program_cache());
  QueryVariant split = exact_each_query();
  split.near_far = true;
  auto parts = make_query_engine(test::test_context(), s, split, test::test_program_cache());
  whole->set_modes(whole->max_modes());
  parts->set_modes(parts->max_modes());
  CHECK(parts->max_modes() == whole->max_modes());
  for (const Pose& pose :
       {test::pose_at({0.5, 0.2, 3}, 7, {1, 1, 0}), test::pose_at({0.1, -0.3, 1.2}, 23, {0, 1, 2})}) {
    const QueryResult a = whole->query(pose), b = parts->query(pose);
    REQUIRE(a.flags == query_ok);
    CHECK(b.energy == doctest::Approx(a.energy).epsilon(1e-3));
    CHECK((b.force - a.force).norm() <= 1e-3 * a.force.norm());
    // The torque is the small remainder of lever-arm terms tens of times larger, each
    // off by the kernel's tolerance: 1 % of it.
    CHECK((b.torque - a.torque).norm() <= 1e-2 * a.torque.norm());
  }
}

TEST_CASE("near field: the background near part ends at the each-query values at a held pose") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene(), 2, true);
  QueryVariant each = exact_each_query();
  each.near_far = true;
  QueryVariant bg = each;
  bg.product_update = ProductUpdate::background;
  auto now = make_query_engine(test::test_context(), pair.spectra, each, test::test_program_cache());
  auto later = make_query_engine(test::test_context(), pair.spectra, bg, test::test_program_cache());
  now->set_modes(8192);
  later->set_modes(8192);
  const Pose start = test::pose_at({0.3, 0.1, 4}, 3, {0, 1, 0}), held = test::pose_at({0.5, 0.2, 3}, 7, {1, 1, 0});
  // Until the worker has made a near part, the far part alone, vouched for by nothing.
  const QueryResult first = later->query(start);
  CHECK(first.error_estimate.energy >= std::abs(first.energy));
  for (int i = 0; i < 300; ++i) {  // the worker makes the near part at `start`
    const QueryResult r = later->query(start);
    if (r.error_estimate.energy < std::abs(r.energy)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  const QueryResult ref = now->query(held);
  QueryResult r;
  for (int i = 0; i < 300; ++i) {  // the workers make the product and the near part for the held pose
    r = later->query(held);
    if (std::abs(r.energy - ref.energy) <= 1e-5 * std::abs(ref.energy) && r.error_estimate.energy > 0) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  CHECK(r.energy == doctest::Approx(ref.energy).epsilon(1e-5));
  CHECK((r.force - ref.force).norm() <= 1e-5 * ref.force.norm());
  CHECK((r.torque - ref.torque).norm() <= 1e-5 * ref.torque.norm());
  // Made at `start` and carried to `held`, the near part was off: that is its staleness.
  CHECK(r.error_estimate.energy > 0);
}

TEST_CASE("near field: a split without a near field, or with a bad width, is refused by name") {
  SmallPair p;
  QueryVariant split = exact_each_query();
  split.near_far = true;
  CHECK_THROWS_WITH_AS(make_query_engine(test::test_context(), p.spectra, split, test::test_program_cache()),
                       doctest::Contains("near field"), Error);
  NearFieldOptions bad;
  bad.width_spacings = 0;
  const FftLibrary fft;
  CHECK_THROWS_WITH_AS(build_near_field(fft, test::test_context(), p.spectra, p.g2, p.rho2, bad),
                       doctest::Contains("width"), Error);
  PairSpectra mixed = p.spectra;
  mixed.part1.sample_parity = 1;  // real against imaginary: the near sum would not be real
  CHECK_THROWS_WITH_AS(build_near_field(fft, test::test_context(), mixed, p.g2, p.rho2, NearFieldOptions{}),
                       doctest::Contains("must be real or both imaginary"), Error);
}

}  // namespace snapfit
