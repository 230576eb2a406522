// The passive bound on the sent force's rate (scheduler/haptics/force_rate_limit.h): a part
// released from a stretched coupling (the pop-in of a peg that rested on a rim) hands the
// force back within the bound, by damping alone (the coupling's energy never rises), with
// the least damping that does it; free motion is never damped; a change that comes from
// the hand is left alone. Where damping cannot help (a part sliding off a ledge drops),
// the sent force is slewed, paid only from the energy the damping removed.
#include <cmath>
#include <doctest/doctest.h>

#include "scheduler/haptics/force_rate_limit.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "snapfit/haptic_loop.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

// A 50 g part on the default coupling (800 N/m, critically damped), millimetres.
CouplingParams coupling() { return make_coupling(1e-3, 0.05, 1e-5, 800, 0.08, 1.0); }

BodyState at(const Vector3d& p) {
  BodyState s;
  s.pose.translation = p;
  return s;
}

// The force step of one step_body with extra damping beta.
double step_with(const BodyState& part, const BodyState& device, double beta, const Vector3d& last) {
  BodyState trial = part;
  ImplicitExtras e;
  e.damping = beta;
  step_body(trial, device, Wrench{}, coupling(), 1e-3, e);
  return (coupling_wrench(trial, device, coupling()).force - last).norm();
}

// A device that follows a function of time.
class MovingDevice : public HapticDevice {
 public:
  explicit MovingDevice(std::function<Vector3d(double)> at) : at_(std::move(at)) {}
  BodyState read(double t) override {
    BodyState s;
    s.pose.translation = at_(t);
    s.velocity = (at_(t + 1e-6) - at_(t - 1e-6)) / 2e-6;
    return s;
  }
  void send(const Wrench&, double) override {}
  DeviceLimits limits() const override { return DeviceLimits{100, 10}; }

 private:
  std::function<Vector3d(double)> at_;
};

LoopReport run(HapticDevice& device, const BodyState& part, double bound, double seconds,
               std::function<ContactWrench(const Pose&)> contact = {}) {
  LoopConfig config;
  config.contact = std::move(contact);
  config.duration_s = seconds;
  config.coupling = coupling();
  config.modes.levels = {1};
  config.passivity_control = false;
  config.max_force_rate_n_per_s = bound;
  WrenchEvaluator none;
  none.evaluate = [](const Pose&) { return QueryResult{}; };
  return run_haptic_loop(device, none, config, simulated_loop_clock(), part);
}

double largest_step(const LoopReport& r) {
  double most = 0;
  for (std::size_t i = 1; i < r.log.size(); ++i)
    most = std::max(most, (r.log[i].sent.force - r.log[i - 1].sent.force).norm());
  return most;
}

}  // namespace

TEST_CASE("force rate: the least damping that keeps a released part's step within the bound") {
  // The part held 6 mm above the hand (4.8 N), at rest, released this frame.
  const BodyState part = at(Vector3d(0, 0, 6)), device = at(Vector3d::Zero());
  const Vector3d last = coupling_wrench(part, device, coupling()).force;
  const double plain = step_with(part, device, 0, last);
  const double beta = rate_limiting_damping(part, device, Wrench{}, coupling(), 1e-3, {}, last, 0.2);
  MESSAGE("plain step " << plain << " N; beta " << beta << " N s/m gives " << step_with(part, device, beta, last)
                        << " N");
  CHECK(plain > 0.5);
  CHECK(step_with(part, device, beta, last) <= 0.2 + 1e-9);
  CHECK(step_with(part, device, 0.99 * beta, last) > 0.2);  // the least that does it
  CHECK(rate_limiting_damping(part, device, Wrench{}, coupling(), 1e-3, {}, last, plain * 1.01) == 0);
}

TEST_CASE("force rate: the hand's own jump is left alone") {
  // The part at rest on the hand; the hand is suddenly 3 mm away: damping the part only
  // makes the step larger.
  const BodyState part = at(Vector3d::Zero()), device = at(Vector3d(3, 0, 0));
  const double beta = rate_limiting_damping(part, device, Wrench{}, coupling(), 1e-3, {}, Vector3d::Zero(), 0.2);
  CHECK(beta == 0);
}

TEST_CASE("force rate: in the loop, a release is handed back within the bound and passively") {
  MovingDevice still([](double) { return Vector3d::Zero(); });
  const BodyState released = at(Vector3d(0, 0, 8));  // 6.4 N stretched
  const LoopReport free_release = run(still, released, 0, 0.5);
  const LoopReport bounded = run(still, released, 200, 0.5);
  // The coupling's energy with the hand still, spring plus the part's kinetic, never
  // rises: the release is slowed by dissipation. The log holds the pose before each step,
  // and backward Euler moves it by dt v', so consecutive poses give the velocity exactly.
  const auto energy = [&](std::size_t i) {  // after step i
    const Vector3d x = 1e-3 * bounded.log[i + 1].part.translation;
    const Vector3d v = 1e-3 * (bounded.log[i + 1].part.translation - bounded.log[i].part.translation) / 1e-3;
    return 0.5 * 800 * x.squaredNorm() + 0.5 * 0.05 * v.squaredNorm();
  };
  double rise = -1;
  for (std::size_t i = 1; i + 1 < bounded.log.size(); ++i) rise = std::max(rise, energy(i) - energy(i - 1));
  MESSAGE("largest step " << largest_step(free_release) << " N unbounded, " << largest_step(bounded)
                          << " N bounded; " << bounded.rate_limited_frames << " frames damped, "
                          << bounded.rate_limit_dissipated_j << " J dissipated; final "
                          << bounded.final_part.pose.translation.z() << " mm");
  CHECK(largest_step(free_release) > 1.0);
  CHECK(largest_step(bounded) <= 0.2 + 1e-9);
  CHECK(rise <= 1e-12);
  CHECK(bounded.rate_limit_dissipated_j > 0);
  CHECK(std::abs(bounded.final_part.pose.translation.z()) < 0.1);  // it still comes home
}

TEST_CASE("force rate: free motion behind a moving hand is never damped") {
  // 20 mm strokes at 1 Hz (peak 0.13 m/s), the part following.
  MovingDevice moving([](double t) { return Vector3d(10 * std::sin(2 * M_PI * t), 0, 0); });
  const LoopReport r = run(moving, at(Vector3d::Zero()), 200, 2.0);
  MESSAGE("largest step " << largest_step(r) << " N, " << r.rate_limited_frames << " frames damped");
  CHECK(r.rate_limited_frames == 0);
}

TEST_CASE("force rate: the sent force's slew pays its work from the tank and only from it") {
  SentForceSlew slew;
  slew.capacity_j = 1e-3;
  const Vector3d hand0(0, 0, 0);
  CHECK(slewed_sent_force(slew, Vector3d(0, 0, 1), hand0, 0.2, 0).isApprox(Vector3d(0, 0, 1)));
  // An empty tank: a 1 N jump goes out as it is.
  CHECK(slewed_sent_force(slew, Vector3d(0, 0, 2), hand0, 0.2, 0).isApprox(Vector3d(0, 0, 2)));
  CHECK(slew.slewed_frames == 0);
  // With energy in the tank the sent force moves by the bound towards the coupling's.
  const Vector3d sent = slewed_sent_force(slew, Vector3d(0, 0, 1), hand0, 0.2, 1e-4);
  CHECK(sent.isApprox(Vector3d(0, 0, 1.8)));
  CHECK(slew.slewed_frames == 1);
  // The hand moves 1 mm down while the 0.8 N offset is held: it took 0.8 mJ... from the
  // hand (the offset points up, the hand moves down), so the tank grows by that work.
  const double tank = slew.tank_j;
  slewed_sent_force(slew, Vector3d(0, 0, 1), Vector3d(0, 0, -1e-3), 0.2, 0);
  CHECK(slew.spent_j == doctest::Approx(0.8 * -1e-3));
  CHECK(slew.tank_j == doctest::Approx(std::min(1e-3, tank + 0.8e-3)));
  // Capacity bounds what is stored.
  SentForceSlew full;
  full.capacity_j = 1e-3;
  slewed_sent_force(full, Vector3d::Zero(), hand0, 0.2, 0);
  slewed_sent_force(full, Vector3d::Zero(), hand0, 0.2, 1.0);
  CHECK(full.tank_j == doctest::Approx(1e-3));
}

TEST_CASE("force rate: a released part stopped by a floor stays within the bound, passively") {
  // The part held 8 mm above the hand (6.4 N) is released while the hand moves down at
  // 5 mm/s; a stiff floor at
  // z = 4 mm (2e5 N/m, integrated implicitly) stops it on the way. The release is slowed
  // by damping; the stop is not something damping can slow (it would take energy), so
  // the sent force is slewed there, paid from the energy the damping removed.
  const auto floor = [](const Pose& p) {
    ContactWrench c;
    const double depth = 4 - p.translation.z();
    if (depth > 0) {
      const double k = 2e5;  // N/m
      c.depth = depth;
      c.wrench.force = Vector3d(0, 0, k * 1e-3 * depth);
      c.energy_j = 0.5 * k * 1e-6 * depth * depth;
      c.stiffness(2, 2) = k;
      c.points = 1;
    }
    return c;
  };
  MovingDevice hand([](double t) { return Vector3d(0, 0, -5 * t); });
  const BodyState released = at(Vector3d(0, 0, 8));
  const LoopReport unbounded = run(hand, released, 0, 0.5, floor);
  const LoopReport bounded = run(hand, released, 200, 0.5, floor);
  MESSAGE("largest step " << largest_step(unbounded) << " N unbounded, " << largest_step(bounded) << " N bounded; "
                          << bounded.rate_limited_frames << " frames damped (" << bounded.rate_limit_dissipated_j
                          << " J), " << bounded.rate_slewed_frames << " slewed (" << bounded.rate_slew_work_j
                          << " J on the hand); final z " << bounded.final_part.pose.translation.z() << " mm");
  CHECK(largest_step(unbounded) > 1.0);
  CHECK(largest_step(bounded) <= 0.2 + 1e-9);
  CHECK(bounded.rate_slewed_frames > 0);
  CHECK(bounded.rate_slew_work_j <= bounded.rate_limit_dissipated_j);
  // Resting on it: the coupling's 800 N/m over 6.5 mm, plus its damper's 0.06 N at the
  // hand's speed, on the floor's 2e5 N/m.
  const double expected = 4 - 1e3 * (800 * 6.5e-3 + coupling().damping * 5e-3) / 2e5;
  CHECK(bounded.final_part.pose.translation.z() == doctest::Approx(expected).epsilon(1e-4));
}
