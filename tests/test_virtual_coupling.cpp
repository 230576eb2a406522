// The virtual coupling and its integrator (scheduler/haptics/virtual_coupling.h): settling
// without overshoot when critically damped, passivity with a stiff coupling, and the
// solid moments the proxy's inertia comes from (mesh/mesh_mass_properties.h).
#include <cmath>
#include <doctest/doctest.h>
#include <random>

#include "mesh/mesh_mass_properties.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "snapfit/error.h"
#include "snapfit/haptic_device.h"
#include "tests/test_meshes.h"
#include "tests/test_support.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

using test::kPi;

BodyState at(const Vector3d& p, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  BodyState s;
  s.pose.translation = p;
  s.pose.rotation = q;
  return s;
}

// Runs `steps` of dt with the device fixed; returns the most negative projection of
// the position error and of the rotation error onto their initial directions
// (relative to the initial size): < 0 means the part went past the device pose.
struct Overshoot {
  double translation = 0, rotation = 0;
  BodyState final_state;
};

Overshoot settle(const CouplingParams& c, BodyState part, const BodyState& device, int steps, double dt) {
  const Vector3d d0 = device.pose.translation - part.pose.translation;
  const Vector3d r0 = rotation_between(part.pose.rotation, device.pose.rotation);
  Overshoot o;
  for (int i = 0; i < steps; ++i) {
    step_body(part, device, Wrench{}, c, dt);
    const Vector3d d = device.pose.translation - part.pose.translation;
    const Vector3d r = rotation_between(part.pose.rotation, device.pose.rotation);
    o.translation = std::min(o.translation, d.dot(d0) / d0.squaredNorm());
    o.rotation = std::min(o.rotation, r.dot(r0) / r0.squaredNorm());
  }
  o.final_state = part;
  return o;
}

}  // namespace

TEST_CASE("virtual coupling: critically damped, the part settles at the device pose without overshoot") {
  // 1 kHz, a 50 g proxy on an 800 N/m coupling (about a desktop device's stiffness).
  const CouplingParams c = make_coupling(1e-3, 0.05, 2e-6, 800, 0.05, 1.0);
  CHECK(c.damping == doctest::Approx(2 * std::sqrt(800 * 0.05)));
  const BodyState device = at({1, 2, -3}, Eigen::Quaterniond(Eigen::AngleAxisd(0.4, Vector3d(1, 1, 0).normalized())));
  const BodyState part = at({6, -1, 2}, Eigen::Quaterniond(Eigen::AngleAxisd(-0.8, Vector3d(0, 0.3, 1).normalized())));
  const Overshoot o = settle(c, part, device, 3000, 1e-3);
  CHECK(o.translation >= -1e-9);
  CHECK(o.rotation >= -1e-6);
  CHECK((o.final_state.pose.translation - device.pose.translation).norm() < 1e-6);
  CHECK(rotation_between(o.final_state.pose.rotation, device.pose.rotation).norm() < 1e-6);
  CHECK(o.final_state.velocity.norm() < 1e-5);

  // The same check does see overshoot when the coupling is underdamped.
  const CouplingParams under = make_coupling(1e-3, 0.05, 2e-6, 800, 0.05, 0.2);
  const Overshoot u = settle(under, part, device, 3000, 1e-3);
  CHECK(u.translation < -0.1);
  CHECK(u.rotation < -0.1);
}

TEST_CASE("virtual coupling: passive with a very stiff coupling over 60 s simulated") {
  // k = 1e5 N/m on 10 g at 1 kHz: omega dt = 3.2, where explicit Euler explodes at once.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (double zeta : {0.0, 1.0}) {
    CAPTURE(zeta);
    const CouplingParams c = make_coupling(1e-3, 0.01, 1e-6, 1e5, 10.0, zeta);
    const BodyState device = at({0, 0, 0});
    BodyState part = at({u(rng) * 5, u(rng) * 5, u(rng) * 5},
                        Eigen::Quaterniond(Eigen::AngleAxisd(2.5, Vector3d(u(rng), u(rng), u(rng)).normalized())));
    part.velocity = Vector3d(u(rng), u(rng), u(rng)) * 100;  // mm / s
    part.angular_velocity = Vector3d(u(rng), u(rng), u(rng)) * 10;
    double energy = coupling_energy(part, device, c);
    const double initial = energy;
    double worst_increase = 0;
    for (int i = 0; i < 60000; ++i) {
      step_body(part, device, Wrench{}, c, 1e-3);
      const double e = coupling_energy(part, device, c);
      REQUIRE(std::isfinite(e));
      worst_increase = std::max(worst_increase, (e - energy) / initial);
      energy = e;
    }
    CHECK(worst_increase <= 1e-12);
    CHECK(energy <= initial);
  }
}

TEST_CASE("virtual coupling: rotations between poses take the short way and invert exp") {
  const Eigen::Quaterniond a(Eigen::AngleAxisd(0.3, Vector3d::UnitZ()));
  const Eigen::Quaterniond b(Eigen::AngleAxisd(-0.2, Vector3d::UnitZ()));
  CHECK((rotation_between(a, b) - Vector3d(0, 0, -0.5)).norm() < 1e-12);
  // 350 degrees one way is 10 degrees the other.
  const Eigen::Quaterniond c(Eigen::AngleAxisd(350 * kPi / 180, Vector3d::UnitX()));
  CHECK((rotation_between(Eigen::Quaterniond::Identity(), c) - Vector3d(-10 * kPi / 180, 0, 0)).norm() < 1e-12);
  const Vector3d theta(0.4, -1.1, 0.7);
  CHECK((rotation_between(Eigen::Quaterniond::Identity(), rotation_exp(theta)) - theta).norm() < 1e-12);
  CHECK_THROWS_AS(make_coupling(1e-3, 0.0, 1e-6, 800, 0.05, 1.0), Error);
  CHECK_THROWS_AS(make_coupling(1e-3, 0.05, 1e-6, NAN, 0.05, 1.0), Error);
}

TEST_CASE("device limits: wrenches are scaled to the limits keeping their direction, and NaN becomes zero") {
  const DeviceLimits limits{3.0, 0.1};
  Wrench w{Vector3d(0, 4, 3), Vector3d(0.05, 0, 0)};
  const Wrench c = clamp_to_limits(w, limits);
  CHECK((c.force - Vector3d(0, 2.4, 1.8)).norm() < 1e-12);
  CHECK((c.torque - w.torque).norm() == 0);
  w.torque.x() = NAN;
  const Wrench z = clamp_to_limits(w, limits);
  CHECK(z.force.norm() == 0);
  CHECK(z.torque.norm() == 0);
  CHECK(clamp_to_limits(Wrench{Vector3d(1, 0, 0), Vector3d(1, 0, 0)}, DeviceLimits{5, 0}).torque.norm() == 0);
}

TEST_CASE("solid moments: a regular prism against its closed form") {
  // Peg: a regular 64-gon prism of circumradius R. Per fan triangle (apex at the axis),
  // int |q|^2 dA = (A_t / 6)(2 R^2 + R^2 cos t), t = 2 pi / 64, so <x^2 + y^2> =
  // (R^2 / 6)(2 + cos t); along the axis z uniform on [z0, z1].
  const double R = 1.5, L = 4.0;
  const Mesh peg = make_procedural_part({"peg", {{"radius", R}, {"length", L}, {"chamfer", 0}}, {}});
  double z0 = 1e300, z1 = -1e300;
  for (const Vector3d& v : peg.vertices) z0 = std::min(z0, v.z()), z1 = std::max(z1, v.z());
  REQUIRE(z1 - z0 == doctest::Approx(L));
  const double t = 2 * kPi / 64;
  const double expected = R * R / 6 * (2 + std::cos(t)) + (z0 * z0 + z0 * z1 + z1 * z1) / 3;
  const SolidMoments m = solid_moments(peg);
  CHECK(m.volume == doctest::Approx(64 * 0.5 * R * R * std::sin(t) * L).epsilon(1e-12));
  CHECK(m.mean_square_radius == doctest::Approx(expected).epsilon(1e-12));
  // About another origin: the parallel-axis shift <|q - o|^2> = <|q|^2> - 2 o.<q> + |o|^2.
  const Vector3d o(0.5, -1, 2);
  const double centroid_z = 0.5 * (z0 + z1);
  CHECK(solid_moments(peg, o).mean_square_radius ==
        doctest::Approx(expected - 2 * o.z() * centroid_z + o.squaredNorm()).epsilon(1e-12));
  CHECK_THROWS_AS(solid_moments(Mesh{}), Error);
}
