// Stiff cases with the real engine: sharp skeletons (sigma 0.15) and large
// penalty factors (lambda up to 1e3) on a small peg-and-hole pair, a virtual coupling at
// a device's maximum stiffness, and the haptic loop run in simulated time for 60 s with
// the device held still in contact. The loop must stay finite, must not oscillate with
// growing amplitude, and must be passive: the total energy (coupling + kinetic,
// scheduler/haptics/virtual_coupling.h coupling_energy, plus the geometric potential
// gain * E * metres_per_unit) never rises above its start by more than a stated tolerance.
#include <algorithm>
#include <cmath>
#include <doctest/doctest.h>
#include <iostream>
#include <memory>

#include "engine/query/query_engine.h"
#include "scheduler/haptics/haptic_setup.h"
#include "snapfit/haptic_loop.h"
#include "tests/stability_support.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

// A device whose handle is held still (a user pressing the part into contact).
class StaticDevice : public HapticDevice {
 public:
  StaticDevice(const Pose& pose, DeviceLimits limits) : limits_(limits) { state_.pose = pose; }
  BodyState read(double) override { return state_; }
  void send(const Wrench& w, double) override { last_ = w; }
  DeviceLimits limits() const override { return limits_; }
  Wrench last_;

 private:
  BodyState state_;
  DeviceLimits limits_;
};

struct EnergyTrace {
  std::vector<double> total;   // J, before each frame's step
  std::vector<double> speed;   // |v| of the part, scene units / s
  double potential_scale = 0;  // J per engine energy unit
};

// Rebuilds the part's state before each frame from the log (the step is x' = x + dt v',
// R' = exp(dt w') R, so velocities follow exactly from consecutive poses) and sums the
// coupling's energy and the geometric potential at that state.
EnergyTrace energy_trace(const LoopReport& r, const BodyState& start, const BodyState& device, const CouplingParams& c,
                         double gain, double dt) {
  EnergyTrace t;
  t.potential_scale = gain * c.metres_per_unit;
  BodyState prev = start, cur = start;
  for (std::size_t k = 0; k < r.log.size(); ++k) {
    if (k > 0) {
      cur.pose = r.log[k - 1].part;
      prev.pose = k > 1 ? r.log[k - 2].part : start.pose;
      cur.velocity = (cur.pose.translation - prev.pose.translation) / dt;
      cur.angular_velocity = rotation_between(prev.pose.rotation, cur.pose.rotation) / dt;
    }
    t.total.push_back(coupling_energy(cur, device, c) + t.potential_scale * r.log[k].energy);
    t.speed.push_back(cur.velocity.norm());
  }
  return t;
}

struct StiffRun {
  LoopReport report;
  EnergyTrace energy;
  double gain = 0;
  CouplingParams coupling;
};

struct StiffPair {
  Scene scene;
  AssemblyPair pair;
  std::unique_ptr<QueryEngine> engine;
  std::size_t modes = 0;
};

StiffPair stiff_pair(const test::SmallPairParams& params, double stiffness) {
  StiffPair s;
  s.scene = test::small_peg_hole_scene(params);
  s.scene.haptics.stiffness_n_per_m = stiffness;
  s.pair = test::build_small_pair(s.scene);
  s.engine = make_query_engine(test::test_context(), s.pair.spectra,
                               query_variant_for(s.scene, Interpolation::tricubic), test::test_program_cache());
  s.modes = std::min<std::size_t>(2048, s.engine->max_modes());
  s.engine->set_modes(s.modes);
  return s;
}

// The device held at `device_pose`; the part starts at rest at the device pose; the
// gain from the scene's geometry_strength (scheduler/haptics/haptic_setup.h).
StiffRun run_static_contact(StiffPair& s, double strength, const Pose& device_pose, double seconds, bool passivity) {
  Scene scene = s.scene;
  scene.haptics.geometry_strength = strength;
  QueryEngine& engine = *s.engine;
  StiffRun run;
  run.coupling = coupling_for(scene, s.pair.parts.part2.mesh);
  double force_scale = 0;
  for (const QueryResult& q : engine.query_batch(gain_probe_poses(scene, s.pair.spectra.spacing)))
    force_scale = std::max(force_scale, q.force.norm());
  run.gain = geometry_gain_for(scene, s.pair.spectra.spacing, force_scale);

  LoopConfig config;
  config.duration_s = seconds;
  config.coupling = run.coupling;
  config.geometry_gain = run.gain;
  config.modes.levels = {s.modes};
  config.passivity_control = passivity;
  // The whole geometric wrench, whatever its error estimate: the energy accounting below
  // uses the whole potential (tests/test_wrench_trust.cpp tests the trust).
  config.trust.enabled = false;
  StaticDevice device(device_pose, device_limits_for(scene));
  WrenchEvaluator eval{[&](const Pose& p) { return engine.query(p); }, [&](std::size_t m) { engine.set_modes(m); }};
  BodyState start;
  start.pose = device_pose;
  run.report = run_haptic_loop(device, eval, config, simulated_loop_clock(), start);
  run.energy = energy_trace(run.report, start, device.read(0), run.coupling, run.gain, 1.0 / config.rate_hz);
  return run;
}

double max_of(const std::vector<double>& v, std::size_t from, std::size_t to) {
  return *std::max_element(v.begin() + from, v.begin() + to);
}

}  // namespace

TEST_CASE(
    "stability stiff: sigma 0.15, lambda 1e3, coupling at a device's maximum stiffness, 60 s static contact is "
    "passive") {
  // The peg pressed 1 mm sideways into the wall of the zero-clearance hole, 8 mm deep,
  // tilted 2 degrees: the device holds it there. 14,500 N/m: the closed-loop stiffness
  // of a Force Dimension omega.x, among the stiffest desktop devices.
  Pose device_pose;
  device_pose.translation = Vector3d(1.0, 0, -8);
  device_pose.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(2 * M_PI / 180, Vector3d::UnitY()));
  constexpr double kStiffness = 14500;
  struct Case {
    const char* name;
    double sigma, lambda_in, lambda_out, strength;
  };
  std::vector<StiffPair> pairs;
  for (const Case& c : {Case{"sigma 0.15, lambda_in 1e3, lambda_out 1, geometry_strength 2 (default)", 0.15, 1e3, 1, 2},
                        Case{"sigma 0.15, lambda_in 1e3, lambda_out 1e3, geometry_strength 32", 0.15, 1e3, 1e3, 32}}) {
    CAPTURE(c.name);
    test::SmallPairParams params;
    params.sigma = c.sigma;
    params.lambda_in = c.lambda_in;
    params.lambda_out = c.lambda_out;
    pairs.push_back(stiff_pair(params, kStiffness));
    const StiffRun run = run_static_contact(pairs.back(), c.strength, device_pose, 60, true);
    const LoopReport& r = run.report;
    REQUIRE(r.frames == 60000);
    CHECK(r.flagged_frames == 0);
    CHECK(r.part_resets == 0);
    for (const FrameRecord& f : r.log) {
      REQUIRE(f.part.is_finite());
      REQUIRE(f.sent.force.allFinite());
      REQUIRE(f.sent.torque.allFinite());
      REQUIRE(std::isfinite(f.energy));
    }
    const std::vector<double>& w = run.energy.total;
    const double w0 = w.front();
    const double w_max = *std::max_element(w.begin(), w.end());
    const double w_min = *std::min_element(w.begin(), w.end());
    const double w_end = w.back();
    // Energy created: the largest rise of the total above its running minimum.
    double created = 0, running_min = w0;
    for (double x : w) running_min = std::min(running_min, x), created = std::max(created, x - running_min);
    const double dissipated = w0 - w_min;
    // Oscillation amplitude: the largest speed in the first second and in the last 10 s.
    const double v_first = max_of(run.energy.speed, 0, 1000);
    const double v_last = max_of(run.energy.speed, w.size() - 10000, w.size());
    std::cout << "stiff contact (" << c.name << "): gain " << run.gain << " N/unit; total energy start " << w0
              << " J, max " << w_max << " J, min " << w_min << " J, end " << w_end
              << " J; largest rise above the running minimum " << created << " J = " << created / dissipated
              << " of the energy dissipated; passivity controller active in " << r.passivity_frames
              << " frames, removed " << r.passivity_dissipated_j << " J; peak speed first 1 s " << v_first
              << " mm/s, last 10 s " << v_last << " mm/s\n";
    // Passive: the total never exceeds its start, ends lower, and no rise above the
    // running minimum exceeds 5% of the energy the run dissipates (the explicit step's
    // and the float sums' error, removed by the controller).
    CHECK(w_max <= w0);
    CHECK(w_end <= w0);
    CHECK(created <= 0.05 * dissipated);
    // No growth late in the run: the last 50 s never exceed the total at 10 s.
    // Float noise of E: the query's float sums (tests/test_stability_accumulation.cpp)
    CHECK(max_of(w, 10000, w.size()) <= w[10000] + 1e-5 * std::abs(w0));
    // No oscillation: the part comes to rest.
    CHECK(v_last <= v_first);
    CHECK(v_last < 1e-3);
  }

  // The same stiff geometry without the passivity controller (LoopConfig::passivity_control
  // = false, the loop without the passivity controller): the explicit geometric step is unstable; after
  // 10 s the part still oscillates at metres per second and energy has been created.
  const StiffRun off = run_static_contact(pairs.back(), 32, device_pose, 10, false);
  const std::vector<double>& w = off.energy.total;
  const double v_last = max_of(off.energy.speed, w.size() - 2000, w.size());
  double created = 0, running_min = w.front();
  for (double x : w) running_min = std::min(running_min, x), created = std::max(created, x - running_min);
  std::cout << "stiff contact without the passivity controller (geometry_strength 32): peak speed in the last 2 s "
            << v_last << " mm/s; largest rise above the running minimum " << created << " J\n";
  CHECK(v_last > 100);  // mm/s: still oscillating
  CHECK(created > 0.1);
}
