// The share of the engine's wrench the loop renders (scheduler/haptics/wrench_trust.h): its
// closed form at the ends and inside the ramp, its continuity, the smaller of force and
// torque, and in the loop: a wrench its estimate cannot vouch for is not rendered.
#include <cmath>
#include <doctest/doctest.h>

#include "scheduler/haptics/scripted_device.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "scheduler/haptics/wrench_trust.h"
#include "snapfit/haptic_loop.h"

using namespace snapfit;

TEST_CASE("wrench trust: 1 within the tolerance, 0 once the error reaches the value, linear between") {
  // relative 0.2, floor 0.05: a 1 N force.
  CHECK(quantity_trust(1.0, 0.0, 0.2, 0.05) == 1.0);
  CHECK(quantity_trust(1.0, 0.2, 0.2, 0.05) == 1.0);  // at the tolerance
  CHECK(quantity_trust(1.0, 1.0, 0.2, 0.05) == 0.0);  // the error as large as the force
  CHECK(quantity_trust(1.0, 5.0, 0.2, 0.05) == 0.0);
  // Midway: 1 - (0.6 - 0.2) / 0.8 = 0.5.
  CHECK(quantity_trust(1.0, 0.6, 0.2, 0.05) == doctest::Approx(0.5).epsilon(1e-12));
  CHECK(quantity_trust(-1.0, 0.6, 0.2, 0.05) == doctest::Approx(0.5).epsilon(1e-12));  // sign-free
  // The floor governs a small force: 0.01 N with an estimate of 0.04 N is vouched for.
  CHECK(quantity_trust(0.01, 0.04, 0.2, 0.05) == 1.0);
  // Beyond it: zero once the error reaches floor + 0.8 v = 0.058.
  CHECK(quantity_trust(0.01, 0.054, 0.2, 0.05) == doctest::Approx(0.5).epsilon(1e-9));
  CHECK(quantity_trust(0.01, 0.06, 0.2, 0.05) == 0.0);
  // A zero value: whatever the floor allows, else nothing (there is nothing to render).
  CHECK(quantity_trust(0.0, 0.01, 0.2, 0.05) == 1.0);
  CHECK(quantity_trust(0.0, 0.1, 0.2, 0.05) == 0.0);
  // Non-finite inputs are never vouched for.
  CHECK(quantity_trust(std::nan(""), 0.0, 0.2, 0.05) == 0.0);
  CHECK(quantity_trust(1.0, INFINITY, 0.2, 0.05) == 0.0);
}

TEST_CASE("wrench trust: continuous in the error and the value, and never opposing a covered exact force") {
  double last = 1;
  for (int i = 0; i <= 2000; ++i) {  // error from 0 to 2 N against a 1 N force
    const double w = quantity_trust(1.0, i * 1e-3, 0.2, 0.05);
    CHECK(std::abs(w - last) <= 1e-3 / 0.8 + 1e-12);
    CHECK(w <= last);
    last = w;
  }
  // With the relative tolerance governing (|F| >= 0.25 N here), any exact force within the
  // estimate of the computed one has a positive dot product with it whenever w > 0.
  const Eigen::Vector3d f(0.6, -0.3, 0.2);
  for (double e : {0.05, 0.2, 0.4, 0.6, 0.69, 0.8}) {
    const double w = quantity_trust(f.norm(), e, 0.2, 0.05);
    if (w == 0) continue;
    for (int k = 0; k < 26; ++k) {  // the worst exact forces lie on the sphere of radius e about f
      Eigen::Vector3d dir((k % 3) - 1.0, (k / 3 % 3) - 1.0, (k / 9 % 3) - 1.0);
      if (dir.norm() == 0) dir = Eigen::Vector3d::UnitX();
      const Eigen::Vector3d exact = f + e * dir.normalized();
      CHECK((w * f).dot(exact) > 0);
    }
  }
}

TEST_CASE("wrench trust: the whole wrench by the smaller of the force's and the torque's weights, off renders all") {
  WrenchTrust t;
  Wrench w{Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0.01, 0)};
  CHECK(wrench_trust(w, ErrorEstimate{0, 0.1, 0.001}, t) == 1.0);
  CHECK(wrench_trust(w, ErrorEstimate{0, 0.6, 0.001}, t) == doctest::Approx(0.5));
  // torque 0.01 N m, its error 0.006: 1 - (0.006 - 0.002) / 0.008 = 0.5.
  CHECK(wrench_trust(w, ErrorEstimate{0, 0.1, 0.006}, t) == doctest::Approx(0.5));
  CHECK(wrench_trust(w, ErrorEstimate{0, 2.0, 0.006}, t) == 0.0);
  t.enabled = false;
  CHECK(wrench_trust(w, ErrorEstimate{0, 2.0, 0.006}, t) == 1.0);
}

namespace {

// A device that holds one pose and keeps the last wrench sent.
struct HeldDevice : HapticDevice {
  BodyState state;
  BodyState read(double) override { return state; }
  void send(const Wrench&, double) override {}
  DeviceLimits limits() const override { return {}; }
};

LoopConfig trust_loop_config() {
  LoopConfig c;
  c.rate_hz = 1000;
  c.duration_s = 0.2;
  c.budget_ms = 1.0;
  c.coupling = make_coupling(1e-3, 0.05, 2e-6, 800, 0.05, 1.0);
  c.geometry_gain = 0.01;  // N per engine force unit
  c.modes.levels = {4096};
  return c;
}

// An engine whose force is 100 units (1 N at the gain) along +x, with an estimated error
// of `error` units.
WrenchEvaluator constant_engine(double error) {
  WrenchEvaluator e;
  e.evaluate = [error](const Pose&) {
    QueryResult r;
    r.energy = -5;
    r.force = Eigen::Vector3d(100, 0, 0);
    r.error_estimate = {1, error, 0};
    r.modes = 4096;
    return r;
  };
  e.set_modes = [](std::size_t) {};
  return e;
}

}  // namespace

TEST_CASE("wrench trust in the loop: what the estimate vouches for is rendered, what it does not is withheld") {
  HeldDevice device;
  for (const auto& [error, expected] : {std::pair{10.0, 1.0}, {60.0, 0.5}, {150.0, 0.0}}) {
    CAPTURE(error);
    LoopConfig c = trust_loop_config();
    const LoopReport r = run_haptic_loop(device, constant_engine(error), c, simulated_loop_clock(), device.state);
    REQUIRE(!r.log.empty());
    for (const FrameRecord& f : r.log) {
      CHECK(f.trust == doctest::Approx(expected));
      CHECK(f.geometric.force.x() == doctest::Approx(expected * 1.0));
      CHECK(f.geometric_error.force == doctest::Approx(0.01 * error));  // the estimate, with the gain
    }
    CHECK(r.trust_withheld_frames == (expected == 0 ? r.frames : 0));
    CHECK(r.trust_scaled_frames == (expected > 0 && expected < 1 ? r.frames : 0));
    // The part, free otherwise, is pushed by what is rendered and no more.
    if (expected == 0) CHECK(r.final_part.pose.translation.norm() < 1e-9);
    if (expected > 0) CHECK(r.final_part.pose.translation.x() > 0);
    // Off: the whole wrench whatever the estimate.
    c.trust.enabled = false;
    const LoopReport all = run_haptic_loop(device, constant_engine(error), c, simulated_loop_clock(), device.state);
    CHECK(all.log.back().trust == 1.0);
    CHECK(all.log.back().geometric.force.x() == doctest::Approx(1.0));
  }
}
