// Per-pose queries (include/snapfit/query.h, engine/spectra/spectra.h; docs/design.md "Correlation in
// the Fourier domain") against closed forms: both parts are anisotropic Gaussians,
// rho_n(p) = i a_n exp(-1/2 (p - m_n)^T B_n (p - m_n)), part 2's off-centre in its own
// frame so the torque about its origin is not zero. With part 2 at (R, t) its Gaussian
// has centre v = t + R m2 and precision Q = R B2 R^T, and
//     f(R, t) = (i a1)(i a2) (2 pi)^{3/2} det(P + Q)^{-1/2} exp(-1/2 d^T (P^-1 + Q^-1)^-1 d),
// P = B1, d = m1 - v (exact over all space; the sample grids cut tails below 1e-8).
// The closed form is itself checked against a brute-force physical-domain sum.
// Derivatives of the closed form come from double-precision central differences.
//
// Measured figures (interpolation error against exact spectra per scheme and
// oversampling, truncation error against m', derivative agreement) are printed with
// MESSAGE on every run; the asserted tolerances are those figures with a margin.
#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <complex>
#include <cstdio>
#include <doctest/doctest.h>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "core/grid.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/spectra/fft3d.h"
#include "engine/query/query_engine.h"
#include "engine/spectra/spectra.h"
#include "snapfit/error.h"
#include "snapfit/pose.h"
#include "snapfit/query.h"
#include "tests/test_support.h"

using namespace snapfit;
using Eigen::Matrix3d;
using Eigen::Vector3d;
using cd = std::complex<double>;

namespace {

using test::kPi;

// ---------------------------------------------------------------- the analytic scene

struct Gaussian {
  double amplitude = 1;  // rho = i * amplitude * exp(...)
  Vector3d mean = Vector3d::Zero();
  Matrix3d precision = Matrix3d::Identity();

  cd value(const Vector3d& p) const {
    const Vector3d d = p - mean;
    return cd(0.0, amplitude * std::exp(-0.5 * d.dot(precision * d)));
  }
};

Matrix3d precision_from(const Vector3d& sigmas, const Eigen::AngleAxisd& axes) {
  const Matrix3d r = axes.toRotationMatrix();
  return r * sigmas.cwiseProduct(sigmas).cwiseInverse().asDiagonal() * r.transpose();
}

// Closed form of f(R, t) = integral rho1(p) rho2(R^T (p - t)) dV.
cd exact_score(const Gaussian& g1, const Gaussian& g2, const Matrix3d& r, const Vector3d& t) {
  const Matrix3d p = g1.precision;
  const Matrix3d q = r * g2.precision * r.transpose();
  const Vector3d d = g1.mean - (t + r * g2.mean);
  const Matrix3d m = (p.inverse() + q.inverse()).inverse();
  const double integral = std::pow(2 * kPi, 1.5) / std::sqrt((p + q).determinant()) * std::exp(-0.5 * d.dot(m * d));
  return cd(0, g1.amplitude) * cd(0, g2.amplitude) * integral;
}

struct Derivatives {
  double energy = 0;
  Vector3d force = Vector3d::Zero();   // Re df/dt
  Vector3d torque = Vector3d::Zero();  // Re df/dtheta, R -> exp(theta [e]x) R
};

// Energy, force and torque of the closed form; derivatives by central differences in
// double (step 1e-5: truncation ~1e-10 and rounding ~1e-11 relative).
Derivatives exact_derivatives(const Gaussian& g1, const Gaussian& g2, const Matrix3d& r, const Vector3d& t) {
  constexpr double step = 1e-5;
  Derivatives out;
  out.energy = -exact_score(g1, g2, r, t).real();
  for (int a = 0; a < 3; ++a) {
    const Vector3d e = Vector3d::Unit(a);
    out.force[a] =
        (exact_score(g1, g2, r, t + step * e).real() - exact_score(g1, g2, r, t - step * e).real()) / (2 * step);
    const Matrix3d plus = Eigen::AngleAxisd(step, e).toRotationMatrix() * r;
    const Matrix3d minus = Eigen::AngleAxisd(-step, e).toRotationMatrix() * r;
    out.torque[a] = (exact_score(g1, g2, plus, t).real() - exact_score(g1, g2, minus, t).real()) / (2 * step);
  }
  return out;
}

// A sample grid of `n` points per axis centred at `centre`.
GridSpec sample_grid(const Vector3d& centre, double spacing, int n) {
  GridSpec g;
  g.spacing = spacing;
  g.dims = Eigen::Vector3i(n, n, n);
  g.origin = centre - 0.5 * spacing * (n - 1) * Vector3d::Ones();
  return g;
}

std::vector<Complex> sample(const Gaussian& g, const GridSpec& grid) {
  std::vector<Complex> out(grid.count());
  for (int k = 0; k < grid.dims.z(); ++k)
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const cd v = g.value(grid.point(i, j, k));
        out[grid.index(i, j, k)] = Complex(static_cast<float>(v.real()), static_cast<float>(v.imag()));
      }
  return out;
}

// Largest value of the Gaussian (relative to its amplitude) on the grid's box faces:
// on the plane x_a = c the maximum of exp(-1/2 x^T B x) is exp(-1/2 (c - m_a)^2 / C_aa).
double tail_at_faces(const Gaussian& g, const GridSpec& grid) {
  const Matrix3d cov = g.precision.inverse();
  const Vector3d last = grid.point(grid.dims.x() - 1, grid.dims.y() - 1, grid.dims.z() - 1);
  double worst = 0;
  for (int a = 0; a < 3; ++a)
    for (double c : {grid.origin[a], last[a]}) {
      const double d = c - g.mean[a];
      worst = std::max(worst, std::exp(-0.5 * d * d / cov(a, a)));
    }
  return worst;
}

struct GaussianPair {
  double spacing = 0.25;
  int points = 32;
  Gaussian g1, g2;
  GridSpec grid1, grid2;
  std::vector<Complex> rho1, rho2;

  GaussianPair() {
    // sigmas 1.6 h .. 2.4 h and 1.5 h .. 2.4 h, both anisotropic and tilted.
    g1.amplitude = 1.3;
    g1.mean = Vector3d(0.3, -0.2, 0.15);
    g1.precision = precision_from(Vector3d(0.40, 0.50, 0.60), Eigen::AngleAxisd(0.4, Vector3d(1, -1, 2).normalized()));
    g2.amplitude = 0.8;
    g2.mean = Vector3d(0.6, -0.4, 0.35);  // off part 2's frame origin: non-zero torque
    g2.precision = precision_from(Vector3d(0.375, 0.50, 0.60), Eigen::AngleAxisd(0.7, Vector3d(2, 1, -1).normalized()));
    // Grids not exactly centred on the means (the spectra must not rely on it).
    grid1 = sample_grid(g1.mean + Vector3d(0.03, -0.05, 0.02), spacing, points);
    grid2 = sample_grid(g2.mean + Vector3d(-0.04, 0.02, 0.05), spacing, points);
    rho1 = sample(g1, grid1);
    rho2 = sample(g2, grid2);
  }

  Matrix3d rotation(const Pose& pose) const { return pose.rotation.toRotationMatrix(); }
  cd score(const Pose& pose) const { return exact_score(g1, g2, rotation(pose), pose.translation); }
  Derivatives derivatives(const Pose& pose) const {
    return exact_derivatives(g1, g2, rotation(pose), pose.translation);
  }
  // Part 2's Gaussian centred on part 1's after the rotation, then moved by `offset`.
  Pose pose(const Eigen::AngleAxisd& rotation, const Vector3d& offset) const {
    Pose p;
    p.rotation = Eigen::Quaterniond(rotation).normalized();
    p.translation = g1.mean - p.rotation.toRotationMatrix() * g2.mean + offset;
    return p;
  }
  // The normalisation of relative errors: |f| at the best aligned pose (identity, centred).
  double score_scale() const { return std::abs(score(pose(Eigen::AngleAxisd::Identity(), Vector3d::Zero()))); }

  // Brute force: sum over part 1's samples of rho1(p_i) rho2(R^T (p_i - t)) h^3, rho2 exact.
  cd brute_force(const Pose& pose) const {
    const Matrix3d rt = rotation(pose).transpose();
    const double h3 = spacing * spacing * spacing;
    cd sum = 0;
    for (int k = 0; k < grid1.dims.z(); ++k)
      for (int j = 0; j < grid1.dims.y(); ++j)
        for (int i = 0; i < grid1.dims.x(); ++i) {
          const Vector3d p = grid1.point(i, j, k);
          sum += g1.value(p) * g2.value(rt * (p - pose.translation));
        }
    return sum * h3;
  }
};

const GaussianPair& pair() {
  static const GaussianPair s;
  return s;
}

// Ten poses: identity, rotations of 30 .. 180 degrees about several axes (four within
// a degree of 180), translations of up to ~2.5 h off the aligned position.
std::vector<Pose> standard_poses() {
  const GaussianPair& s = pair();
  using A = Eigen::AngleAxisd;
  const double deg = kPi / 180;
  return {
      s.pose(A::Identity(), Vector3d::Zero()),
      s.pose(A::Identity(), Vector3d(0.5, -0.25, 0.3)),
      s.pose(A(30 * deg, Vector3d(1, 2, 3).normalized()), Vector3d(-0.2, 0.1, 0.35)),
      s.pose(A(90 * deg, Vector3d::UnitX()), Vector3d(0.25, 0.25, -0.25)),
      s.pose(A(179 * deg, Vector3d::UnitY()), Vector3d(0.1, -0.4, 0.2)),
      s.pose(A(180 * deg, Vector3d::UnitZ()), Vector3d(-0.3, 0.0, 0.15)),
      s.pose(A(179.5 * deg, Vector3d(1, 1, 0).normalized()), Vector3d(0.0, 0.3, -0.45)),
      s.pose(A(120 * deg, Vector3d(1, 1, 1).normalized()), Vector3d(0.4, 0.2, 0.1)),
      s.pose(A(60 * deg, Vector3d(-1, 0.5, 2).normalized()), Vector3d(-0.35, -0.3, 0.0)),
      s.pose(A(179.7 * deg, Vector3d(0.3, -1, 0.2).normalized()), Vector3d(0.2, 0.35, 0.3)),
  };
}

// Random poses: uniform rotations (fixed seed) plus three within half a degree of
// 180 degrees, translations up to 2 h off the aligned position.
std::vector<Pose> random_poses(std::size_t count, unsigned seed) {
  const GaussianPair& s = pair();
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0, 1);
  std::uniform_real_distribution<double> off(-0.5, 0.5);
  std::vector<Pose> out;
  for (std::size_t n = 0; n < count; ++n) {
    Eigen::Quaterniond q(normal(rng), normal(rng), normal(rng), normal(rng));
    Eigen::AngleAxisd aa(q.normalized());
    if (n % 3 == 2) aa.angle() = kPi + (n % 2 == 0 ? -0.3 : 0.3) * kPi / 180;  // 179.7 or 180.3 degrees
    out.push_back(s.pose(aa, Vector3d(off(rng), off(rng), off(rng))));
  }
  return out;
}

// ---------------------------------------------------------------- device, spectra, engines

const ComputeContext& context() {
  static const ComputeContext ctx = make_compute_context(select_device(""));
  return ctx;
}

const test::TempDir& program_dir() {
  static const test::TempDir dir;
  return dir;
}

ProgramCacheConfig cache_config() {
  ProgramCacheConfig c;
  c.directory = program_dir().file("programs");
  c.note = [](const std::string&) {};
  return c;
}

// Spectra are computed once per oversampling and kept (host data). Each computation
// holds its own FftLibrary (clFFT set-up and teardown are process-wide, as in test_fft3d).
const PairSpectra& spectra(double oversampling) {
  static std::map<double, PairSpectra> cache;
  auto it = cache.find(oversampling);
  if (it == cache.end()) {
    const FftLibrary library;
    SpectrumOptions options;
    options.oversampling = oversampling;
    const GaussianPair& s = pair();
    it =
        cache.emplace(oversampling, compute_pair_spectra(library, context(), s.grid1, s.rho1, s.grid2, s.rho2, options))
            .first;
  }
  return it->second;
}

QueryVariant variant(Interpolation interpolation, bool force, bool torque, bool translation_only = false) {
  QueryVariant v;
  v.interpolation = interpolation;
  v.force = force;
  v.torque = torque;
  v.translation_only = translation_only;
  return v;
}

std::unique_ptr<QueryEngine> make_engine(double oversampling, const QueryVariant& v) {
  auto engine = make_query_engine(context(), spectra(oversampling), v, cache_config());
  engine->set_modes(engine->max_modes());
  return engine;
}

const char* name(Interpolation i) { return i == Interpolation::tricubic ? "tricubic" : "trilinear"; }

std::string fmt(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

double rel(double a, double b) { return std::abs(a - b) / std::max({std::abs(a), std::abs(b), 1e-300}); }

}  // namespace

// ============================================================================ 1. accuracy

TEST_CASE("pose query: the closed form matches a brute-force physical-domain sum, and the grids hold the fields") {
  const GaussianPair& s = pair();
  CHECK(tail_at_faces(s.g1, s.grid1) < 1e-8);
  CHECK(tail_at_faces(s.g2, s.grid2) < 1e-8);
  const double scale = s.score_scale();
  double worst = 0;
  for (const Pose& pose : standard_poses()) {
    const cd exact = s.score(pose), brute = s.brute_force(pose);
    worst = std::max(worst, std::abs(exact - brute) / scale);
    CHECK(exact.real() < 0);  // (i a1)(i a2) > 0 overlap: f real and negative, E = -Re f > 0
    CHECK(std::abs(exact.imag()) == 0.0);
  }
  MESSAGE("closed form vs brute-force sum over part 1's samples: max |diff| / |f_aligned| = " << fmt("%.2e", worst));
  CHECK(worst < 1e-9);
}

TEST_CASE("pose query: all modes: interpolation error against exact spectra per scheme and oversampling") {
  const GaussianPair& s = pair();
  const std::vector<Pose> poses = standard_poses();
  const double scale = s.score_scale();
  double force_scale = 0;
  for (const Pose& p : poses) force_scale = std::max(force_scale, s.derivatives(p).force.norm());

  // error[scheme][oversampling]: max over poses of |f - f_exact| / |f_aligned|, and of
  // the force error / max |F_exact|.
  std::map<Interpolation, std::map<double, double>> score_error, force_error;
  std::ostringstream table;
  table << "interpolation error against the closed form, all modes, max over " << poses.size()
        << " poses (|f - f_exact| / |f_aligned|; force |F - F_exact| / max|F_exact|):\n"
        << "  scheme     oversampling  dims     modes      score err   force err   worst pose  ms/query\n";
  for (const double os : {1.5, 2.0, 3.0}) {
    for (const Interpolation interp : {Interpolation::trilinear, Interpolation::tricubic}) {
      auto engine = make_engine(os, variant(interp, true, false));
      const PairSpectra& sp = spectra(os);
      REQUIRE(engine->max_modes() == sp.dims[0] * sp.dims[1] * sp.dims[2]);
      double err = 0, ferr = 0, seconds = 0;
      std::size_t worst_pose = 0;
      for (std::size_t n = 0; n < poses.size(); ++n) {
        const QueryResult r = engine->query(poses[n]);
        REQUIRE(r.flags == query_ok);
        CHECK(r.modes == engine->max_modes());
        const cd exact = s.score(poses[n]);
        const Derivatives d = s.derivatives(poses[n]);
        const double e = std::abs(r.score - exact) / scale;
        if (e > err) worst_pose = n;
        err = std::max(err, e);
        ferr = std::max(ferr, (r.force - d.force).norm() / force_scale);
        // E = -Re f, reported consistently with the score.
        CHECK(std::abs(r.energy + r.score.real()) <= 1e-6 * scale);
        seconds += r.seconds;
      }
      score_error[interp][os] = err;
      force_error[interp][os] = ferr;
      table << "  " << (interp == Interpolation::tricubic ? "tricubic " : "trilinear") << "  " << fmt("%4.1f", os)
            << "          " << sp.dims[0] << "^3" << (sp.dims[0] < 100 ? "    " : "   ")
            << fmt("%-9.0f", double(engine->max_modes())) << "  " << fmt("%.2e", err) << "    " << fmt("%.2e", ferr)
            << "    " << worst_pose << "           " << fmt("%.1f", 1e3 * seconds / poses.size()) << "\n";
    }
  }
  // Observed order p of the error in the node spacing (1 / oversampling):
  // err(os_a) / err(os_b) = (os_b / os_a)^p.
  auto order = [&](Interpolation i, double a, double b) {
    return std::log(score_error[i][a] / score_error[i][b]) / std::log(b / a);
  };
  table << "  observed order in 1/oversampling (1.5->2, 2->3): trilinear "
        << fmt("%.2f", order(Interpolation::trilinear, 1.5, 2.0)) << ", "
        << fmt("%.2f", order(Interpolation::trilinear, 2.0, 3.0)) << "; tricubic "
        << fmt("%.2f", order(Interpolation::tricubic, 1.5, 2.0)) << ", "
        << fmt("%.2f", order(Interpolation::tricubic, 2.0, 3.0));
  MESSAGE(table.str());

  for (const double os : {1.5, 2.0, 3.0}) {
    // Catmull-Rom (order ~4 here) beats trilinear (order 2) at every oversampling.
    CHECK(score_error[Interpolation::tricubic][os] < 0.1 * score_error[Interpolation::trilinear][os]);
    CHECK(force_error[Interpolation::tricubic][os] < 0.1 * force_error[Interpolation::trilinear][os]);
  }
  // More zero padding = finer frequency nodes = smaller interpolation error, at the
  // scheme's order (measured 2.0 and 3.9-4.0; asserted with margin).
  for (const auto& [a, b] : {std::pair<double, double>{1.5, 2.0}, {2.0, 3.0}}) {
    CHECK(order(Interpolation::trilinear, a, b) > 1.5);
    CHECK(order(Interpolation::tricubic, a, b) > 3.0);
  }
  // Tolerances: the measured errors (PoCL CPU, float spectra) with a margin of ~3x.
  CHECK(score_error[Interpolation::trilinear][1.5] < 3e-2);    // measured 9.0e-3
  CHECK(score_error[Interpolation::trilinear][2.0] < 1.5e-2);  // 5.1e-3
  CHECK(score_error[Interpolation::trilinear][3.0] < 7e-3);    // 2.3e-3
  CHECK(score_error[Interpolation::tricubic][1.5] < 6e-4);     // 1.9e-4
  CHECK(score_error[Interpolation::tricubic][2.0] < 2e-4);     // 6.0e-5
  CHECK(score_error[Interpolation::tricubic][3.0] < 4e-5);     // 1.2e-5
  CHECK(force_error[Interpolation::trilinear][2.0] < 1.5e-2);  // 4.2e-3
  CHECK(force_error[Interpolation::tricubic][2.0] < 2e-4);     // 7.0e-5
}

TEST_CASE("pose query: error against the closed form falls as m' grows") {
  const GaussianPair& s = pair();
  const std::vector<Pose> poses = standard_poses();
  const double scale = s.score_scale();
  auto engine = make_engine(2.0, variant(Interpolation::tricubic, true, false));
  const std::size_t all = engine->max_modes();
  const std::vector<std::size_t> counts = {100, 300, 1000, 3000, 10000, 30000, 100000, all};
  std::vector<double> errors;
  std::ostringstream table;
  table << "truncation: tricubic, oversampling 2, max over " << poses.size()
        << " poses of |f - f_exact| / |f_aligned|\n"
        << "  m'        error\n";
  for (const std::size_t m : counts) {
    engine->set_modes(m);
    REQUIRE(engine->modes() == m);
    double err = 0;
    for (const Pose& p : poses) {
      const QueryResult r = engine->query(p);
      REQUIRE(r.modes == m);
      err = std::max(err, std::abs(r.score - s.score(p)) / scale);
    }
    errors.push_back(err);
    table << "  " << fmt("%-9.0f", double(m)) << " " << fmt("%.2e", err) << "\n";
  }
  MESSAGE(table.str());
  const double floor = errors.back();  // the interpolation error (previous test)
  for (std::size_t n = 1; n < errors.size(); ++n) {
    INFO("m' = " << counts[n] << " after " << counts[n - 1]);
    // Non-increasing, allowing wiggles of 10% or at the level of the interpolation floor.
    CHECK(errors[n] <= 1.1 * errors[n - 1] + 2 * floor);
  }
  CHECK(errors.front() > 0.5);     // 100 modes is a coarse low-pass (measured 0.89)
  CHECK(errors[4] < 3e-2);         // 1e4 modes: 1.7e-2
  CHECK(errors[5] < 5e-4);         // 3e4 modes: 1.8e-4
  CHECK(errors[6] < 1.5 * floor);  // 1e5 modes: at the interpolation floor (4.15e-5 both)
}

// ============================================================================ 3. derivatives

namespace {

// Central differences of the engine's own energy: F_a = -dE/dt_a (step dt), and
// T_a = -dE/dtheta_a for R -> exp(theta [e_a]x) R (step dtheta), from one batch.
struct EngineDifferences {
  QueryResult at;
  Vector3d force, torque;
};

EngineDifferences engine_differences(QueryEngine& engine, const Pose& pose, double dt, double dtheta) {
  std::vector<Pose> batch = {pose};
  for (int a = 0; a < 3; ++a)
    for (const double sign : {1.0, -1.0}) {
      Pose moved = pose;
      moved.translation[a] += sign * dt;
      batch.push_back(moved);
      Pose turned = pose;
      turned.rotation =
          (Eigen::Quaterniond(Eigen::AngleAxisd(sign * dtheta, Vector3d::Unit(a))) * pose.rotation).normalized();
      batch.push_back(turned);
    }
  const std::vector<QueryResult> r = engine.query_batch(batch);
  EngineDifferences out;
  out.at = r[0];
  for (int a = 0; a < 3; ++a) {
    out.force[a] = -(r[1 + 4 * a].energy - r[3 + 4 * a].energy) / (2 * dt);
    out.torque[a] = -(r[2 + 4 * a].energy - r[4 + 4 * a].energy) / (2 * dtheta);
  }
  return out;
}

// Rotations at or within a degree of a symmetry of the cubic frequency lattice
// (90 deg about x, ~180 deg about y, z and a face diagonal, 120 deg about the body
// diagonal): there most rotated frequencies sit on or next to grid nodes.
std::vector<Pose> lattice_symmetry_poses() {
  const std::vector<Pose> p = standard_poses();
  return {p[3], p[4], p[5], p[6], p[7]};
}

}  // namespace

TEST_CASE("pose query: force and torque match central differences of the engine's energy and the closed form") {
  const GaussianPair& s = pair();
  const std::vector<Pose> generic = random_poses(9, 2024);  // three of them at 179.7 / 180.3 deg
  const std::vector<Pose> symmetric = lattice_symmetry_poses();
  std::vector<Pose> all = generic;
  all.insert(all.end(), symmetric.begin(), symmetric.end());

  double force_scale = 0, torque_scale = 0;
  for (const Pose& p : all) {
    const Derivatives d = s.derivatives(p);
    force_scale = std::max(force_scale, d.force.norm());
    torque_scale = std::max(torque_scale, d.torque.norm());
  }
  REQUIRE(torque_scale > 0.1 * force_scale);  // the off-centre Gaussian gives real torque
  constexpr std::size_t kModes = 100000;      // converged at oversampling 2 (see the m' test)

  // Errors relative to max |F_exact| and max |T_exact| over the poses.
  enum { f_fd, t_fd_generic, t_fd_symmetric, f_exact, t_exact, fd_f_exact, fd_t_exact_generic, columns };
  std::map<Interpolation, std::map<double, std::array<double, columns>>> worst;
  std::ostringstream table;
  table << "derivatives, oversampling 2, m' = " << kModes << ", " << generic.size() << " generic + " << symmetric.size()
        << " lattice-symmetric poses; errors / max|F_exact|, / max|T_exact|; FD = central differences of the engine's "
           "energy\n"
        << "  scheme     step(h,rad) |F-FD|     |T-FD|gen  |T-FD|sym  |F-exact|  |T-exact|  |FD_F-ex|  |FD_T-ex|gen\n";
  for (const Interpolation interp : {Interpolation::trilinear, Interpolation::tricubic}) {
    auto engine = make_engine(2.0, variant(interp, true, true));
    engine->set_modes(kModes);
    for (const double step : {1e-3, 3e-3, 1e-2}) {
      std::array<double, columns> w{};
      for (std::size_t n = 0; n < all.size(); ++n) {
        const Pose& pose = all[n];
        const bool is_generic = n < generic.size();
        const EngineDifferences e = engine_differences(*engine, pose, step * s.spacing, step);
        REQUIRE(e.at.flags == query_ok);
        const Derivatives exact = s.derivatives(pose);
        auto up = [&](int column, double value) { w[column] = std::max(w[column], value); };
        up(f_fd, (e.at.force - e.force).norm() / force_scale);
        up(is_generic ? t_fd_generic : t_fd_symmetric, (e.at.torque - e.torque).norm() / torque_scale);
        up(f_exact, (e.at.force - exact.force).norm() / force_scale);
        up(t_exact, (e.at.torque - exact.torque).norm() / torque_scale);
        up(fd_f_exact, (e.force - exact.force).norm() / force_scale);
        if (is_generic) up(fd_t_exact_generic, (e.torque - exact.torque).norm() / torque_scale);
        if (step == 1e-2) {
          // Signs and directions: the engine's force and torque are the closed form's.
          INFO("pose " << n << ": rotation (xyzw) " << pose.rotation.coeffs().transpose() << ", translation "
                       << pose.translation.transpose());
          INFO("engine F " << e.at.force.transpose() << ", exact F " << exact.force.transpose());
          INFO("engine T " << e.at.torque.transpose() << ", exact T " << exact.torque.transpose());
          CHECK(e.at.force.dot(exact.force) > 0.99 * e.at.force.norm() * exact.force.norm());
          const double cosine = interp == Interpolation::tricubic ? 0.99 : 0.95;
          CHECK(e.at.torque.dot(exact.torque) > cosine * e.at.torque.norm() * exact.torque.norm());
        }
      }
      worst[interp][step] = w;
      table << "  " << (interp == Interpolation::tricubic ? "tricubic " : "trilinear") << "  " << fmt("%-8.0e", step)
            << "    ";
      for (double v : w) table << fmt("%.2e", v) << "   ";
      table << "\n";
    }
  }

  MESSAGE(table.str());

  for (const Interpolation interp : {Interpolation::trilinear, Interpolation::tricubic}) {
    const std::string scheme = name(interp);
    CAPTURE(scheme);
    const auto& w = worst[interp][1e-2];
    // Translations need no interpolation: the force is the energy's gradient to float
    // rounding (measured 1.8e-5 / 1.9e-5 at step 1e-2 h; 2e-4 at 1e-3 h, rounding-bound).
    CHECK(w[f_fd] < 1e-4);
    CHECK(worst[interp][3e-3][f_fd] < 2e-4);
    CHECK(w[fd_f_exact] < (interp == Interpolation::tricubic ? 3e-4 : 2e-2));
  }
  const auto& cubic = worst[Interpolation::tricubic][1e-2];
  const auto& linear = worst[Interpolation::trilinear][1e-2];
  // Against the closed form. The torque is the rotational derivative of the interpolated
  // spectrum, one order below its values: tricubic 3.8e-3, trilinear 0.12 (a trilinear
  // interpolant's slope is piecewise constant), force 7e-5 / 4.8e-3 (measured).
  CHECK(cubic[f_exact] < 3e-4);
  CHECK(cubic[t_exact] < 1e-2);
  CHECK(linear[f_exact] < 2e-2);
  CHECK(linear[t_exact] < 0.25);
  // The torque is the derivative of the engine's own energy: against its central
  // differences only the differences' truncation remains (tricubic, measured 1.2e-4 at
  // step 1e-2 rad and 2.4e-5 at 3e-3 generic; 6e-5 at 1e-3 near lattice symmetries, where
  // the rotated frequencies sit on the nodes and the energy curves more).
  CHECK(cubic[t_fd_generic] < 5e-4);
  CHECK(worst[Interpolation::tricubic][3e-3][t_fd_generic] < 1e-4);
  CHECK(cubic[t_fd_symmetric] < 3e-3);
  CHECK(worst[Interpolation::tricubic][1e-3][t_fd_symmetric] < 3e-4);
  // Trilinear: consistent at generic rotations (measured 8e-4); at lattice symmetries the
  // interpolant is only C0 at the nodes, the torque is a one-sided slope there and the
  // central difference averages two (measured 0.053). A sign or factor error reads ~1.
  CHECK(linear[t_fd_generic] < 3e-3);
  CHECK(linear[t_fd_symmetric] < 0.15);
}

// ============================================================================ 4. variants

TEST_CASE("pose query: translation-only and force-only variants agree with the 6-DOF variant") {
  const GaussianPair& s = pair();
  const double scale = s.score_scale();
  double force_scale = 0;
  std::vector<Pose> poses;
  for (const Vector3d& off :
       {Vector3d(0, 0, 0), Vector3d(0.5, -0.25, 0.3), Vector3d(-0.6, 0.1, 0.45), Vector3d(0.2, 0.7, -0.3)}) {
    poses.push_back(s.pose(Eigen::AngleAxisd::Identity(), off));
    force_scale = std::max(force_scale, s.derivatives(poses.back()).force.norm());
  }
  for (const Interpolation interp : {Interpolation::trilinear, Interpolation::tricubic}) {
    const std::string scheme = name(interp);
    CAPTURE(scheme);
    auto full = make_engine(2.0, variant(interp, true, true));
    auto force_only = make_engine(2.0, variant(interp, true, false));
    auto translation = make_engine(2.0, variant(interp, true, false, true));
    double d_translation = 0, d_force_only = 0, d_exact = 0;
    bool force_only_bit_exact = true;
    for (const Pose& p : poses) {
      const QueryResult a = full->query(p), b = force_only->query(p), c = translation->query(p);
      REQUIRE(a.flags == query_ok);
      REQUIRE(b.flags == query_ok);
      REQUIRE(c.flags == query_ok);
      d_translation =
          std::max({d_translation, std::abs(c.score - a.score) / scale, (c.force - a.force).norm() / force_scale});
      d_force_only =
          std::max({d_force_only, std::abs(b.score - a.score) / scale, (b.force - a.force).norm() / force_scale});
      force_only_bit_exact = force_only_bit_exact && b.energy == a.energy && b.force == a.force;
      const Derivatives d = s.derivatives(p);
      d_exact = std::max({d_exact, std::abs(c.score - s.score(p)) / scale, (c.force - d.force).norm() / force_scale});
      CHECK(b.torque == Vector3d::Zero());
      CHECK(c.torque == Vector3d::Zero());
    }
    MESSAGE(std::string(name(interp)) << ": at R = I, translation-only vs 6-DOF: " << fmt("%.2e", d_translation)
                                      << "; force-only vs force+torque: " << fmt("%.2e", d_force_only)
                                      << std::string(force_only_bit_exact ? " (bit-exact)" : "")
                                      << "; translation-only vs closed form: " << fmt("%.2e", d_exact));
    // At R = I the rotated frequencies are the grid nodes: both schemes reproduce the
    // node values (Catmull-Rom interpolates), so only float rounding differs.
    CHECK(d_translation < 1e-5);
    CHECK(d_force_only < 1e-6);
    CHECK(d_exact < 1e-4);
  }
}

TEST_CASE("pose query: translation-only sums exactly the m' lowest-|w| modes at any m'") {
  // translation_lines sums, per x-line, the interval of kx that engine/query/translation_lines.h
  // selects from the |w| order; at R = I the 6-DOF kernel reads the nodes themselves from the |w|-sorted list, so
  // the two agree to float rounding at every m' only if both sum the same mode set.
  const GaussianPair& s = pair();
  const double scale = s.score_scale();
  auto six = make_engine(2.0, variant(Interpolation::trilinear, true, false));
  auto translation = make_engine(2.0, variant(Interpolation::trilinear, true, false, true));
  const std::size_t all = translation->max_modes();
  const std::vector<Vector3d> offsets = {Vector3d(0, 0, 0), Vector3d(0.5, -0.25, 0.3), Vector3d(-1.6, 0.9, 2.45)};
  double force_scale = 0;
  for (const Vector3d& off : offsets)
    force_scale = std::max(force_scale, s.derivatives(s.pose(Eigen::AngleAxisd::Identity(), off)).force.norm());
  double worst = 0;
  for (const std::size_t m : {std::size_t(1), std::size_t(2), std::size_t(7), std::size_t(33), std::size_t(100),
                              std::size_t(1234), std::size_t(4097), std::size_t(20000), all - 1, all}) {
    CAPTURE(m);
    six->set_modes(m);
    translation->set_modes(m);
    for (const Vector3d& off : offsets) {
      const Pose p = s.pose(Eigen::AngleAxisd::Identity(), off);
      const QueryResult a = six->query(p), b = translation->query(p);
      REQUIRE(a.flags == query_ok);
      REQUIRE(b.flags == query_ok);
      CHECK(b.modes == m);
      worst = std::max({worst, std::abs(b.score - a.score) / scale, (b.force - a.force).norm() / force_scale});
    }
  }
  MESSAGE("translation-only (dense line intervals) vs 6-DOF at R = I over m' in 1 .. all: max relative diff "
          << fmt("%.2e", worst));
  CHECK(worst < 1e-5);
}

TEST_CASE("pose query: phase tables built in the kernel match a double-precision host sum") {
  // The kernel builds exp(2 pi i k tau_a / L_a) itself from tau / L as a float pair,
  // reduced to a fraction of a turn (kernels/pose_query.cl axis_phase). Checked against
  // sum_k W_k exp(2 pi i w_k.tau) in double over every mode, W_k = S1(w_k) S2(-w_k) dw,
  // at translations up to the aliasing limit (large k tau / L).
  const GaussianPair& s = pair();
  const PairSpectra& sp = spectra(2.0);
  auto engine = make_engine(2.0, variant(Interpolation::trilinear, true, false, true));
  const auto& d = sp.dims;
  const double dw = 1.0 / (sp.length.x() * sp.length.y() * sp.length.z());
  auto signed_k = [](std::size_t k, std::size_t n) { return k <= n / 2 ? double(k) : double(k) - double(n); };
  double worst = 0, scale = 0;
  int used = 0;
  for (const Vector3d& off :
       {Vector3d(0.3, -0.2, 0.1), Vector3d(2.7, -3.1, 1.9), Vector3d(-4.4, 3.3, -2.6), Vector3d(5.1, 4.9, -5.3)}) {
    const Pose p = s.pose(Eigen::AngleAxisd::Identity(), off);
    const QueryResult r = engine->query(p);
    if (r.flags != query_ok) continue;
    ++used;
    const Vector3d tau = p.translation + sp.part2.centre - sp.part1.centre;  // R = I
    cd f = 0;
    Vector3d force = Vector3d::Zero();
    for (std::size_t z = 0; z < d[2]; ++z)
      for (std::size_t y = 0; y < d[1]; ++y)
        for (std::size_t x = 0; x < d[0]; ++x) {
          const std::size_t k = x + d[0] * (y + d[1] * z);
          const std::size_t neg = (d[0] - x) % d[0] + d[0] * ((d[1] - y) % d[1] + d[1] * ((d[2] - z) % d[2]));
          const Vector3d w(signed_k(x, d[0]) / sp.length.x(), signed_k(y, d[1]) / sp.length.y(),
                           signed_k(z, d[2]) / sp.length.z());
          const cd weight = cd(sp.part1.rho[k]) * cd(sp.part2.rho[neg]) * dw;
          const cd term = weight * std::exp(cd(0, 2 * kPi * w.dot(tau)));
          f += term;
          force += -2 * kPi * term.imag() * w;  // Re(2 pi i w term)
        }
    scale = std::max(scale, s.score_scale());
    worst = std::max({worst, std::abs(r.score - f) / scale, (r.force - force).norm() / (2 * kPi * scale / sp.spacing)});
  }
  REQUIRE(used >= 3);
  MESSAGE("kernel phase tables vs a double-precision host sum over all "
          << engine->max_modes() << " modes, " << used << " translations up to the aliasing limit: max error "
          << fmt("%.2e", worst) << " of |f| aligned");
  CHECK(worst < 1e-5);
}

TEST_CASE("pose query: a half-float cube stays within its stated error of the float cube") {
  // QueryVariant::half_cube stores S2 and SQ as half floats (11 significant bits),
  // each scaled by 1 / (largest component). Measured against the float cube at random
  // poses including near 180 degrees, relative to the largest |f|, |F|, |T| over them.
  const std::vector<Pose> poses = random_poses(12, 11);
  for (const Interpolation interp : {Interpolation::trilinear, Interpolation::tricubic}) {
    const std::string scheme = name(interp);
    CAPTURE(scheme);
    QueryVariant half = variant(interp, true, true);
    half.half_cube = true;
    auto a = make_engine(2.0, variant(interp, true, true));
    auto b = make_engine(2.0, half);
    for (const std::size_t m : {std::size_t(5000), a->max_modes()}) {
      a->set_modes(m);
      b->set_modes(m);
      double fs = 0, ff = 0, ft = 0, df = 0, dF = 0, dT = 0;
      for (const Pose& p : poses) {
        const QueryResult x = a->query(p), y = b->query(p);
        REQUIRE(x.flags == y.flags);
        fs = std::max(fs, std::abs(x.score));
        ff = std::max(ff, x.force.norm());
        ft = std::max(ft, x.torque.norm());
        df = std::max(df, std::abs(y.score - x.score));
        dF = std::max(dF, (y.force - x.force).norm());
        dT = std::max(dT, (y.torque - x.torque).norm());
      }
      MESSAGE(
          scheme << ", m' " << m << ": half cube vs float cube, relative to the largest value over the poses: score "
                 << fmt("%.2e", df / fs) << ", force " << fmt("%.2e", dF / ff) << ", torque " << fmt("%.2e", dT / ft));
      // Measured about 1e-5 (score 3e-6): below trilinear's interpolation error (5e-3)
      // and tricubic's (6e-5) at oversampling 2.
      CHECK(df / fs < 5e-5);
      CHECK(dF / ff < 5e-5);
      CHECK(dT / ft < 5e-5);
    }
  }
}

// ============================================================================ 5. batch

TEST_CASE("pose query: query_batch equals a loop of query") {
  const std::vector<Pose> poses = random_poses(12, 7);
  for (const Interpolation interp : {Interpolation::trilinear, Interpolation::tricubic}) {
    const std::string scheme = name(interp);
    CAPTURE(scheme);
    auto engine = make_engine(1.5, variant(interp, true, true));
    engine->set_modes(5000);
    const std::vector<QueryResult> batch = engine->query_batch(poses);
    REQUIRE(batch.size() == poses.size());
    bool bit_exact = true;
    double worst = 0;
    for (std::size_t n = 0; n < poses.size(); ++n) {
      const QueryResult one = engine->query(poses[n]);
      CHECK(batch[n].flags == one.flags);
      CHECK(batch[n].modes == one.modes);
      bit_exact = bit_exact && batch[n].score == one.score && batch[n].force == one.force &&
                  batch[n].torque == one.torque && batch[n].energy == one.energy;
      const double s = std::max(std::abs(one.score), 1e-30);
      worst = std::max({worst, std::abs(batch[n].score - one.score) / s,
                        (batch[n].force - one.force).norm() / std::max(one.force.norm(), 1e-30),
                        (batch[n].torque - one.torque).norm() / std::max(one.torque.norm(), 1e-30)});
    }
    MESSAGE(std::string(name(interp)) << ": batch vs loop: " << std::string(bit_exact ? "bit-exact" : "not bit-exact")
                                      << ", max relative diff " << fmt("%.2e", worst));
    CHECK(worst <= 1e-6);
    CHECK(engine->query_batch({}).empty());
  }
}

TEST_CASE("pose query: results do not depend on the launch shape, down to one work-item per group") {
  // Work-groups of 1 to 256 items and 1 to 16 groups per pose (the engine's environment
  // overrides, engine/query/query_launch.h) against the device's own shape: the same sums in
  // another order. A group of fewer than 8 items once wrote only its first outputs (the
  // exact-rotation lines share that reduction: tests/oclgrind covers them).
  const std::vector<Pose> poses = random_poses(6, 5);
  Pose along;
  along.translation = Vector3d(0.1, -0.2, 0.15);
  const std::vector<std::pair<QueryVariant, std::vector<Pose>>> cases = {
      {variant(Interpolation::tricubic, true, true), poses},
      {variant(Interpolation::trilinear, true, false, true), {along}}};
  for (const auto& [v, at] : cases) {
    auto results = [&](const char* wg, const char* groups) {
      test::EnvScope w("SNAPFIT_QUERY_WG", wg), g("SNAPFIT_QUERY_GROUPS", groups);
      auto engine = make_query_engine(context(), spectra(1.5), v, cache_config());
      engine->set_modes(3000);
      return engine->query_batch(at);
    };
    const std::vector<QueryResult> own = results(nullptr, nullptr);
    for (const auto& [wg, groups] : std::vector<std::pair<const char*, const char*>>{
             {"1", "3"}, {"2", "1"}, {"4", "16"}, {"8", "2"}, {"256", "5"}}) {
      const std::vector<QueryResult> other = results(wg, groups);
      for (std::size_t n = 0; n < at.size(); ++n) {
        CAPTURE(wg);
        CAPTURE(groups);
        CAPTURE(n);
        CHECK(std::abs(other[n].score - own[n].score) <= 1e-5 * std::abs(own[n].score));
        CHECK((other[n].force - own[n].force).norm() <= 1e-5 * own[n].force.norm());
        CHECK((other[n].torque - own[n].torque).norm() <= 1e-5 * std::max(own[n].torque.norm(), 1e-30));
      }
    }
  }
}

// ============================================================================ 6. modes

TEST_CASE("pose query: set_modes clamps and results report m'") {
  auto engine = make_engine(1.5, variant(Interpolation::trilinear, true, false));
  const PairSpectra& sp = spectra(1.5);
  const std::size_t all = sp.dims[0] * sp.dims[1] * sp.dims[2];
  CHECK(engine->max_modes() == all);
  const Pose pose = standard_poses()[3];
  for (const auto& [asked, expected] :
       std::vector<std::pair<std::size_t, std::size_t>>{{0, 1},
                                                        {1, 1},
                                                        {1234, 1234},
                                                        {all - 1, all - 1},
                                                        {all, all},
                                                        {all + 1, all},
                                                        {std::numeric_limits<std::size_t>::max(), all}}) {
    CAPTURE(asked);
    engine->set_modes(asked);
    CHECK(engine->modes() == expected);
    const QueryResult r = engine->query(pose);
    CHECK(r.modes == expected);
    CHECK(engine->query_batch({pose, pose})[1].modes == expected);
  }
  // One mode is the w = 0 term alone: rho1^(0) rho2^(0) dw, i.e. (i a1 V1)(i a2 V2) / L^3
  // with V the Gaussians' volumes integrals; independent of the pose.
  engine->set_modes(1);
  const GaussianPair& s = pair();
  const double v1 = std::pow(2 * kPi, 1.5) / std::sqrt(s.g1.precision.determinant());
  const double v2 = std::pow(2 * kPi, 1.5) / std::sqrt(s.g2.precision.determinant());
  const cd dc = -s.g1.amplitude * v1 * s.g2.amplitude * v2 / (sp.length[0] * sp.length[1] * sp.length[2]);
  for (const Pose& p : standard_poses()) CHECK(std::abs(engine->query(p).score - dc) < 1e-5 * std::abs(dc));
}

// ============================================================================ 7. flags

TEST_CASE("pose query: poses outside the padded box and bad poses are flagged and return zero") {
  const GaussianPair& s = pair();
  auto engine = make_engine(1.5, variant(Interpolation::tricubic, true, true));
  engine->set_modes(2000);
  const Pose good = standard_poses()[2];
  REQUIRE(engine->query(good).flags == query_ok);
  auto is_zero = [](const QueryResult& r) {
    return r.energy == 0 && r.force == Vector3d::Zero() && r.torque == Vector3d::Zero() && r.score == cd(0);
  };

  const PairSpectra& sp = spectra(1.5);
  for (int a = 0; a < 3; ++a)
    for (const double sign : {-1.0, 1.0}) {
      Pose far = good;
      far.translation[a] += sign * sp.length[a];  // a whole period: would alias back onto the overlap
      const QueryResult r = engine->query(far);
      CAPTURE(far.translation.transpose());
      CHECK((r.flags & query_outside_grid) != 0);
      CHECK(is_zero(r));
    }
  {
    Pose far = good;
    far.translation = Vector3d(1e6, -1e6, 1e6);
    const QueryResult r = engine->query(far);
    CHECK((r.flags & query_outside_grid) != 0);
    CHECK(is_zero(r));
  }

  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  std::vector<Pose> bad;
  for (int c = 0; c < 4; ++c) {
    Pose p = good;
    p.rotation.coeffs()[c] = nan;
    bad.push_back(p);
  }
  for (int a = 0; a < 3; ++a) {
    Pose p = good;
    p.translation[a] = nan;
    bad.push_back(p);
  }
  {
    Pose p = good;
    p.translation.x() = inf;
    bad.push_back(p);
    p = good;
    p.rotation.coeffs() *= 2.0;  // not a unit quaternion
    bad.push_back(p);
    p = good;
    p.rotation.coeffs().setZero();
    bad.push_back(p);
  }
  for (std::size_t n = 0; n < bad.size(); ++n) {
    CAPTURE(n);
    const QueryResult r = engine->query(bad[n]);
    CHECK((r.flags & query_bad_pose) != 0);
    CHECK(is_zero(r));
  }
  // In a batch, bad poses do not spoil their neighbours.
  std::vector<Pose> mixed = {good, bad[0], good, bad[4], good};
  const std::vector<QueryResult> out = engine->query_batch(mixed);
  const QueryResult ref = engine->query(good);
  REQUIRE(out.size() == mixed.size());
  for (std::size_t n : {0u, 2u, 4u}) {
    CHECK(out[n].flags == query_ok);
    CHECK(std::abs(out[n].score - ref.score) <= 1e-6 * std::abs(ref.score));
  }
  CHECK((out[1].flags & query_bad_pose) != 0);
  CHECK((out[3].flags & query_bad_pose) != 0);
  CHECK(is_zero(out[1]));
  CHECK(is_zero(out[3]));
  (void)s;
}

// ============================================================================ 8. errors

TEST_CASE("pose query: the exact rotation needs the deconvolved spectrum, and mismatched spacings throw") {
  const FftLibrary library;
  // A small pair (16^3, no oversampling): too coarse a box for the exact rotation's kernel.
  const GaussianPair& s = pair();
  GridSpec g1 = sample_grid(Vector3d::Zero(), 0.5, 16), g2 = sample_grid(Vector3d::Zero(), 0.5, 16);
  const std::vector<Complex> r1 = sample(s.g1, g1), r2 = sample(s.g2, g2);
  SpectrumOptions options;
  options.oversampling = 1.0;
  const PairSpectra plain = compute_pair_spectra(library, context(), g1, r1, g2, r2, options);
  CHECK(plain.part2.deconvolved.empty());
  QueryVariant exact = variant(Interpolation::tricubic, true, true);
  exact.rotation = RotationMethod::exact_product;
  CHECK_THROWS_AS(make_query_engine(context(), plain, exact, cache_config()), Error);
  // The interpolated variants need nothing more (their torque is the energy's derivative).
  auto ok = make_query_engine(context(), plain, variant(Interpolation::trilinear, true, true), cache_config());
  CHECK(ok->query(Pose{}).flags == query_ok);

  GridSpec other = g2;
  other.spacing = 0.45;
  CHECK_THROWS_AS(compute_pair_spectra(library, context(), g1, r1, other, r2, options), Error);
  try {
    compute_pair_spectra(library, context(), g1, r1, other, r2, options);
    FAIL("mismatched spacings did not throw");
  } catch (const Error& e) {
    MESSAGE("mismatched spacings: " << std::string(e.what()));
  }
}
