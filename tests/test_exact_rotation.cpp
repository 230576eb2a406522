// The exact-rotation strategy (engine/query/rotated_product_query.h, docs/design.md "Exact
// rotation") and the consistency of what the 6-DOF strategies render:
// - at every mode and off-lattice rotations the product engine equals a double-precision
//   sum over part 2's exact rotated spectrum, the DTFT of its samples summed directly;
// - on the shipped parts (coarsened), at aligned, contact, generic and free poses, the
//   force and torque of the interpolated (tricubic) and exact strategies, and of the exact
//   one split into near and far parts, are the central differences of the same engine's
//   energy;
// - the background product update, at a held pose, ends at the each-query values.
#include <Eigen/Geometry>
#include <cmath>
#include <complex>
#include <doctest/doctest.h>
#include <filesystem>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

#include "engine/query/query_engine.h"
#include "engine/spectra/spectra.h"
#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/trajectory.h"
#include "snapfit/query.h"
#include "tests/stability_support.h"

namespace snapfit {
namespace {

using Cd = std::complex<double>;
using Eigen::Matrix3d;
using Eigen::Vector3d;

std::vector<Complex> random_samples(const GridSpec& g, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<float> n(0, 1);
  std::vector<Complex> v(g.count());
  for (Complex& c : v) c = Complex(n(rng), n(rng));
  return v;
}

// S(w) = h^3 sum_j c_j exp(-2 pi i w.(x_j - c)): the spectrum of the samples at any w.
Cd dtft(const GridSpec& g, const std::vector<Complex>& c, const Vector3d& centre, const Vector3d& w) {
  Cd s = 0;
  for (std::size_t j = 0; j < g.count(); ++j) s += Cd(c[j]) * std::exp(Cd(0, -2 * M_PI * w.dot(g.point(j) - centre)));
  return s * std::pow(g.spacing, 3);
}

// E(R, t) = -Re sum_k S1(w_k) S2(-R^T w_k) dw e^{2 pi i w_k.tau} over every mode, S2 by DTFT.
double exact_energy(const PairSpectra& s, const GridSpec& g2, const std::vector<Complex>& c2, const Matrix3d& R,
                    const Vector3d& t) {
  const auto& d = s.dims;
  const double dw = 1.0 / (s.length.x() * s.length.y() * s.length.z());
  const Vector3d tau = t + R * s.part2.centre - s.part1.centre;
  double e = 0;
  for (std::size_t k = 0; k < d[0] * d[1] * d[2]; ++k) {
    const Vector3d w(signed_index(k % d[0], d[0]) / s.length.x(), signed_index((k / d[0]) % d[1], d[1]) / s.length.y(),
                     signed_index(k / (d[0] * d[1]), d[2]) / s.length.z());
    const Cd term = Cd(s.part1.rho[k]) * dw * dtft(g2, c2, s.part2.centre, -(R.transpose() * w)) *
                    std::exp(Cd(0, 2 * M_PI * w.dot(tau)));
    e -= term.real();
  }
  return e;
}

Matrix3d turn(double angle, const Vector3d& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).matrix(); }

// Central differences of an engine's own energy: F = -dE/dt, T = -dE/dtheta under
// R -> exp(theta [e_a]x) R (include/snapfit/query.h).
struct Differences {
  QueryResult at;
  Vector3d force, torque;
};

Differences differences(QueryEngine& engine, const Pose& pose, double dt, double dtheta) {
  Differences out;
  out.at = engine.query(pose);
  for (int a = 0; a < 3; ++a) {
    double e[4];
    for (int n = 0; n < 4; ++n) {
      const double sign = n % 2 ? -1 : 1;
      Pose p = pose;
      if (n < 2)
        p.translation[a] += sign * dt;
      else
        p.rotation = (Eigen::Quaterniond(Eigen::AngleAxisd(sign * dtheta, Vector3d::Unit(a))) * pose.rotation);
      e[n] = engine.query(p).energy;
    }
    out.force[a] = -(e[0] - e[1]) / (2 * dt);
    out.torque[a] = -(e[2] - e[3]) / (2 * dtheta);
  }
  return out;
}

QueryVariant exact_variant(std::size_t product_modes = 0) {
  QueryVariant v;
  v.rotation = RotationMethod::exact_product;
  v.product_update = ProductUpdate::each_query;
  v.product_modes = product_modes;
  return v;
}

// The same exact-rotation engine twice on `pair`: the product made at each query, and
// made by its worker in the background.
std::pair<std::unique_ptr<QueryEngine>, std::unique_ptr<QueryEngine>> now_and_later(const AssemblyPair& pair) {
  QueryVariant background = exact_variant();
  background.product_update = ProductUpdate::background;
  return {make_query_engine(test::test_context(), pair.spectra, exact_variant(), test::test_program_cache()),
          make_query_engine(test::test_context(), pair.spectra, background, test::test_program_cache())};
}

// The background engine's result at a held pose once its worker has made the product
// for it (its energy within 1e-5 of `ref`), or after 2 s.
QueryResult settled(QueryEngine& later, const Pose& pose, const QueryResult& ref) {
  QueryResult r;
  for (int i = 0; i < 200; ++i) {
    r = later.query(pose);
    if (std::abs(r.energy - ref.energy) <= 1e-5 * std::abs(ref.energy)) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return r;
}

}  // namespace

TEST_CASE("exact rotation: every mode at off-lattice rotations equals the double sum over the DTFT of part 2") {
  const GridSpec g1 = test::grid_spec({9, 8, 7}, 0.5, {-2.0, -1.7, -1.4}),
                 g2 = test::grid_spec({5, 6, 4}, 0.5, {0.3, -1.1, 0.2});
  const auto c1 = random_samples(g1, 11), c2 = random_samples(g2, 12);
  const FftLibrary fft;
  const PairSpectra s = compute_pair_spectra(fft, test::test_context(), g1, c1, g2, c2);
  REQUIRE(s.part2.deconvolved_width > 0);

  // The convention: at lattice frequencies the DTFT is the stored spectrum.
  for (std::size_t k : {std::size_t(1), std::size_t(37), std::size_t(400)}) {
    const auto& d = s.dims;
    const Vector3d w(signed_index(k % d[0], d[0]) / s.length.x(), signed_index((k / d[0]) % d[1], d[1]) / s.length.y(),
                     signed_index(k / (d[0] * d[1]), d[2]) / s.length.z());
    const Cd direct = dtft(g2, c2, s.part2.centre, w);
    CHECK(std::abs(direct - Cd(s.part2.rho[k])) < 1e-5 * std::abs(direct) + 1e-4);
  }

  auto engine = make_query_engine(test::test_context(), s, exact_variant(), test::test_program_cache());
  engine->set_modes(engine->max_modes());
  double scale = 0;  // sum of |S1| |S2| dw: the size of the terms
  for (std::size_t k = 0; k < s.part1.rho.size(); ++k) scale += std::abs(s.part1.rho[k]) * std::abs(s.part2.rho[k]);
  scale /= s.length.x() * s.length.y() * s.length.z();
  const std::vector<std::pair<Matrix3d, Vector3d>> poses = {
      {turn(0.37, {1, 2, 3}), {0.2, -0.1, 0.3}},
      {turn(2.2, {-1, 0.5, 0.2}), {-0.4, 0.25, 0.1}},
      {turn(1e-3, {0, 0, 1}), {0.05, 0.0, -0.3}},
  };
  for (const auto& [R, t] : poses) {
    Pose pose;
    pose.rotation = Eigen::Quaterniond(R);
    pose.translation = t;
    const QueryResult q = engine->query(pose);
    REQUIRE(q.flags == query_ok);
    const double e = exact_energy(s, g2, c2, R, t);
    CAPTURE(R);
    CHECK(std::abs(q.energy - e) < 1e-4 * scale);
    // The torque is the exact energy's rotational derivative (double, central, 1e-4 rad).
    const double h = 1e-4;
    for (int a = 0; a < 3; ++a) {
      const double plus = exact_energy(s, g2, c2, turn(h, Vector3d::Unit(a)) * R, t);
      const double minus = exact_energy(s, g2, c2, turn(-h, Vector3d::Unit(a)) * R, t);
      CAPTURE(a);
      CHECK(std::abs(q.torque[a] + (plus - minus) / (2 * h)) < 1e-3 * scale);
    }
  }
}

// A part 2 whose grid alone would give an odd box (2 N2 + 4 = 35 points along x): the box
// is even, and the exact product converges to the DTFT sum as its kernel widens. With an
// odd box the centred spectrum is anti-periodic in its index, the kernel's taps that wrap
// across the edge read it with the wrong sign, and the torque stayed 7 % off at every width.
TEST_CASE("exact rotation: a part whose box would be odd converges to the DTFT sum as the kernel widens") {
  const GridSpec g1 = test::grid_spec({8, 8, 6}, 0.5, {-2.0, -2.0, -1.5}),
                 g2 = test::grid_spec({15, 14, 5}, 0.5, {-3.5, -3.25, -1.0});
  // Sharp-edged samples: a ball of radius 2.7 (1 inside, -0.3 outside), imaginary as the affinity.
  const auto ball = [](const GridSpec& g) {
    std::vector<Complex> v(g.count());
    const Vector3d c = g.point(g.dims.x() / 2, g.dims.y() / 2, g.dims.z() / 2);
    for (std::size_t j = 0; j < v.size(); ++j) v[j] = Complex(0, (g.point(j) - c).norm() < 2.7 ? 1.0f : -0.3f);
    return v;
  };
  const auto c1 = ball(g1), c2 = ball(g2);
  const Matrix3d R = turn(0.37, {1, 2, 3});
  const Vector3d t(0.2, -0.1, 0.3);
  const FftLibrary fft;
  double reference_energy = 0;
  Vector3d reference_torque = Vector3d::Zero();
  for (int width : {5, 9}) {
    CAPTURE(width);
    SpectrumOptions options;
    options.exact_rotation_width = width;
    const PairSpectra s = compute_pair_spectra(fft, test::test_context(), g1, c1, g2, c2, options);
    for (std::size_t d : s.dims) CHECK(d % 2 == 0);
    REQUIRE(s.part2.deconvolved_width == width);
    if (width == 5) {  // the DTFT sum depends on the box, not on the kernel
      reference_energy = exact_energy(s, g2, c2, R, t);
      const double h = 1e-4;
      for (int a = 0; a < 3; ++a)
        reference_torque[a] = -(exact_energy(s, g2, c2, turn(h, Vector3d::Unit(a)) * R, t) -
                                exact_energy(s, g2, c2, turn(-h, Vector3d::Unit(a)) * R, t)) /
                              (2 * h);
    }
    auto engine = make_query_engine(test::test_context(), s, exact_variant(), test::test_program_cache());
    engine->set_modes(engine->max_modes());
    Pose pose;
    pose.rotation = Eigen::Quaterniond(R);
    pose.translation = t;
    const QueryResult q = engine->query(pose);
    REQUIRE(q.flags == query_ok);
    const double energy_error = std::abs(q.energy - reference_energy) / std::abs(reference_energy);
    const double torque_error =
        (Vector3d(q.torque[0], q.torque[1], q.torque[2]) - reference_torque).norm() / reference_torque.norm();
    MESSAGE("kernel width " << width << ": E " << energy_error << ", T " << torque_error << " relative");
    CHECK(energy_error < (width == 5 ? 1e-4 : 1e-5));
    CHECK(torque_error < (width == 5 ? 3e-3 : 1e-4));
  }
}

TEST_CASE("exact rotation: force and torque are the energy's central differences on the shipped parts") {
  namespace fs = std::filesystem;
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::directory_iterator(fs::path(SNAPFIT_SOURCE_DIR) / "scenes"))
    if (entry.path().extension() == ".json") scenes.push_back(entry.path());
  std::sort(scenes.begin(), scenes.end());
  std::ostringstream table;
  table << "consistency on the shipped parts (grid spacing x2): max over poses of |T - T_fd| / max|T|, "
           "|F - F_fd| / max|F|\n";
  int checked = 0;
  for (const fs::path& file : scenes) {
    Scene scene = load_scene(file.string());
    if (scene.motion == Motion::translation || !scene.outputs.torque) continue;
    if (scene.grid.spacing) *scene.grid.spacing *= 2;
    if (scene.grid.resolution) *scene.grid.resolution /= 2;
    const AssemblyPair pair = test::build_small_pair(scene, 2, true);
    const Pose assembled = scene.assembled_pose
                               ? *scene.assembled_pose
                               : trajectory_pose(scene.trajectory, scene.trajectory.keyframes.back().time_s);
    const double h = pair.spectra.spacing;
    std::vector<Pose> poses = {assembled};  // aligned: R as assembled
    Pose contact = assembled;               // tilted 3 degrees and pushed sideways
    contact.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(3 * M_PI / 180, Vector3d::UnitX())) * contact.rotation;
    contact.translation += Vector3d(0.3 * h, 0, 0);
    poses.push_back(contact);
    Pose generic = assembled;  // 25 degrees off, half-way out
    generic.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(25 * M_PI / 180, Vector3d(1, 2, 3).normalized())) * generic.rotation;
    generic.translation += Vector3d(0.1 * h, -0.2 * h, 4 * h);
    poses.push_back(generic);
    Pose free = assembled;  // well above the block
    free.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vector3d(-1, 1, 0.5).normalized())) * free.rotation;
    free.translation += Vector3d(0, 0, 6 * h);
    poses.push_back(free);

    QueryVariant interpolated = query_variant_for(scene, Interpolation::tricubic);
    QueryVariant split = exact_variant();
    split.near_far = true;
    for (const int strategy : {0, 1, 2}) {  // interpolated, exact, exact split into near and far
        const QueryVariant v = strategy == 0 ? interpolated : strategy == 1 ? exact_variant() : split;
      auto engine = make_query_engine(test::test_context(), pair.spectra, v, test::test_program_cache());
      for (const std::size_t modes : {std::size_t(4096), std::size_t(32768)}) {
        engine->set_modes(modes);
        std::vector<Differences> d;
        double t_scale = 0, f_scale = 0;
        for (const Pose& p : poses) {
          d.push_back(differences(*engine, p, 1e-3 * h, 1e-3));
          CAPTURE(file.filename().string());
          CAPTURE(d.size());
          REQUIRE(d.back().at.flags == query_ok);
          t_scale = std::max(t_scale, d.back().at.torque.norm());
          f_scale = std::max(f_scale, d.back().at.force.norm());
        }
        REQUIRE(t_scale > 0);
        double t_gap = 0, f_gap = 0;
        for (std::size_t n = 0; n < poses.size(); ++n) {
          CAPTURE(file.filename().string());
          CAPTURE(strategy);
          CAPTURE(modes);
          CAPTURE(n);
          const double tg = (d[n].at.torque - d[n].torque).norm() / t_scale;
          const double fg = (d[n].at.force - d[n].force).norm() / f_scale;
          t_gap = std::max(t_gap, tg);
          f_gap = std::max(f_gap, fg);
          // Float sums and 1e-3 steps: agreement to ~1e-3 of the largest value. A torque
          // that is not the energy's derivative reads 0.1 - 2 (the moment spectra did).
          CHECK(tg < 5e-3);
          CHECK(fg < 5e-3);
        }
        table << "  " << file.filename().string()
              << (strategy == 2 ? "  near-far    " : strategy == 1 ? "  exact       " : "  interpolated") << "  m' " << modes
              << "  T " << t_gap << "  F " << f_gap << "\n";
        ++checked;
      }
    }
  }
  MESSAGE(table.str());
  CHECK(checked >= 18);  // three 6-DOF scenes, three strategies, two m'
}

TEST_CASE("exact rotation: the background product update ends at the each-query values at a held pose") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  const Pose pose = test::pose_at({0.5, 0.2, 3}, 7, {1, 1, 0});
  auto [now, later] = now_and_later(pair);
  now->set_modes(8192);
  later->set_modes(8192);
  const QueryResult ref = now->query(pose);
  const QueryResult r = settled(*later, pose, ref);
  CHECK(r.energy == doctest::Approx(ref.energy).epsilon(1e-5));
  CHECK((r.force - ref.force).norm() <= 1e-5 * ref.force.norm());
  CHECK((r.torque - ref.torque).norm() <= 1e-5 * ref.torque.norm());
}

TEST_CASE("exact rotation: a larger m' requested of the background product waits for its product, a smaller one does not") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  const Pose pose = test::pose_at({0.5, 0.2, 3}, 7, {1, 1, 0});
  auto [now, later] = now_and_later(pair);
  now->request_modes(2048);  // each query: at once
  CHECK(now->modes() == 2048);
  later->set_modes(2048);
  (void)later->query(pose);  // the first product, made here

  later->request_modes(8192);
  CHECK(later->modes() == 2048);  // the worker makes the product for 8192 modes; the frame keeps 2048
  QueryResult r;
  for (int i = 0; i < 300 && r.modes != 8192; ++i) {
    r = later->query(pose);
    CHECK((r.modes == 2048 || r.modes == 8192));
    if (r.modes != 8192) std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  REQUIRE(r.modes == 8192);
  CHECK(later->modes() == 8192);
  now->set_modes(8192);
  const QueryResult ref = now->query(pose);
  r = settled(*later, pose, ref);
  CHECK(r.energy == doctest::Approx(ref.energy).epsilon(1e-5));

  // Smaller: at once, from the product that covers more modes.
  later->request_modes(1024);
  CHECK(later->modes() == 1024);
  now->set_modes(1024);
  const QueryResult small = later->query(pose), small_ref = now->query(pose);
  CHECK(small.modes == 1024);
  CHECK(small.energy == doctest::Approx(small_ref.energy).epsilon(1e-5));
  CHECK((small.force - small_ref.force).norm() <= 1e-5 * small_ref.force.norm());
}

}  // namespace snapfit
