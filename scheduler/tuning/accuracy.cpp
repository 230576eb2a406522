#include "scheduler/tuning/accuracy.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <thread>

#include "core/progress.h"
#include "core/quantile.h"
#include "engine/query/query_engine.h"
#include "scheduler/haptics/haptic_setup.h"
#include "scheduler/haptics/trajectory.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "scheduler/tuning/engine_tuning.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

QueryVariant exact_product(const QueryVariant& base, ProductUpdate update, std::size_t product_modes) {
  QueryVariant v = base;
  v.rotation = RotationMethod::exact_product;
  v.product_update = update;
  v.product_modes = product_modes;
  return v;
}

std::string percent(double x) {
  std::ostringstream s;
  s.precision(x < 0.1 ? 2 : 3);
  s << 100 * x << " %";
  return s.str();
}

std::string errors_text(const StrategyAccuracy& s) {
  std::string t = "E " + percent(s.energy_error);
  if (s.variant.force) t += ", F " + percent(s.force_error);
  if (s.variant.torque) t += ", T " + percent(s.torque_error);
  return t;
}

// Queries `engine` at `pose`, paced by `period`, until its background product has caught up
// with the pose (its result equals `at_rest`'s, made for the pose, to float rounding) or
// `limit_s` has passed: a hand held still before it turns. A jump to a far pose is no part
// of a turn, and on a busy machine the product for it can take longer than the turn.
void settle_at(QueryEngine& engine, const QueryResult& at_rest, const Pose& pose, double period, double limit_s) {
  const auto start = std::chrono::steady_clock::now();
  const double tolerance = 1e-5 * std::max(1e-30, std::abs(at_rest.energy));
  for (int i = 0;; ++i) {
    const QueryResult r = engine.query(pose);
    if (std::abs(r.energy - at_rest.energy) <= tolerance) return;
    const auto next = start + std::chrono::duration<double>((i + 1) * period);
    if (next - start > std::chrono::duration<double>(limit_s)) return;
    std::this_thread::sleep_until(next);
  }
}

// The background product's error while part 2 turns: from each of `starts` poses, held
// until the product has caught up with it, queries paced at `rate_hz` on the wall clock
// (the worker predicts the rotation from them) along a steady rotation at each speed about
// one of six axes, for 0.2 s; the last query is compared with the exact reference at its
// pose, beside the same m' with the product made for that pose (at rest): the difference
// is what the lag costs.
std::vector<TurningAccuracy> turning_accuracy(const ComputeContext& ctx, const PairSpectra& spectra,
                                              const QueryVariant& background, std::size_t modes,
                                              const std::vector<Pose>& starts, const std::vector<double>& speeds,
                                              double rate_hz) {
  QueryVariant exact = background;  // the reference: every mode of the exact product, unsplit
  exact.product_update = ProductUpdate::each_query;
  exact.product_modes = spectra.part1.rho.size();
  exact.near_far = false;
  auto reference = make_query_engine(ctx, spectra, exact);
  reference->set_modes(reference->max_modes());
  auto engine = make_query_engine(ctx, spectra, background);
  engine->set_modes(modes);
  QueryVariant at_rest_variant = background;
  at_rest_variant.product_update = ProductUpdate::each_query;
  auto at_rest = make_query_engine(ctx, spectra, at_rest_variant);
  at_rest->set_modes(modes);
  const Eigen::Vector3d axes[6] = {Eigen::Vector3d::UnitX(),
                                   Eigen::Vector3d::UnitY(),
                                   Eigen::Vector3d::UnitZ(),
                                   Eigen::Vector3d(1, 1, 0).normalized(),
                                   Eigen::Vector3d(0, 1, 1).normalized(),
                                   Eigen::Vector3d(1, 0, 1).normalized()};
  const double period = 1.0 / (rate_hz > 0 ? rate_hz : 1000.0);
  const int frames = static_cast<int>(std::lround(0.2 / period));
  std::vector<TurningAccuracy> out;
  for (double speed : speeds) {
    RelativeErrors sums, rest;
    for (std::size_t k = 0; k < starts.size(); ++k) {
      const Eigen::Vector3d omega = speed * M_PI / 180.0 * axes[k % 6];
      Pose pose = starts[k];
      settle_at(*engine, at_rest->query(pose), pose, period, 5.0);
      const auto start = std::chrono::steady_clock::now();
      QueryResult last;
      for (int i = 0; i <= frames; ++i) {
        std::this_thread::sleep_until(start + std::chrono::duration<double>(i * period));
        pose.rotation = (rotation_exp(omega * (i * period)) * starts[k].rotation).normalized();
        last = engine->query(pose);
      }
      const QueryResult ref = reference->query(pose), still = at_rest->query(pose);
      if (last.flags == query_ok && ref.flags == query_ok && still.flags == query_ok) {
        sums.add(last, ref);
        rest.add(still, ref);
      }
    }
    out.push_back({speed, sums.relative(0), sums.relative(1), sums.relative(2), rest.relative(0), rest.relative(1),
                   rest.relative(2)});
  }
  return out;
}

}  // namespace

QueryVariant accuracy_base_variant(const Scene& scene) {
  const bool rotation = scene.motion != Motion::translation;
  QueryVariant base;
  base.force = true;
  base.torque = rotation && scene.outputs.torque;
  base.translation_only = !rotation;
  base.interpolation = Interpolation::tricubic;
  return base;
}

std::vector<QueryVariant> accuracy_candidates(const QueryVariant& base, bool near_field) {
  if (base.translation_only) return {base};
  QueryVariant trilinear = base;
  trilinear.interpolation = Interpolation::trilinear;
  std::vector<QueryVariant> candidates{base, trilinear, exact_product(base, ProductUpdate::background, 0)};
  if (near_field) {
    candidates.push_back(candidates.back());
    candidates.back().near_far = true;
  }
  return candidates;
}

double rendered_error(const StrategyAccuracy& s) {
  if (!s.variant.force && !s.variant.torque) return s.energy_error;
  return std::max(s.variant.force ? s.force_error : 0.0, s.variant.torque ? s.torque_error : 0.0);
}

std::size_t lowest_error_that_fits(const std::vector<StrategyAccuracy>& strategies) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < strategies.size(); ++i) {
    const StrategyAccuracy &a = strategies[i], &b = strategies[best];
    if ((a.fits && !b.fits) || (a.fits == b.fits && rendered_error(a) < rendered_error(b))) best = i;
  }
  return best;
}

std::string strategy_short_name(const QueryVariant& v) {
  if (v.translation_only) return "translation lines";
  std::string name = v.rotation == RotationMethod::exact_product  ? "exact product"
                     : v.interpolation == Interpolation::tricubic ? "tricubic"
                                                                  : "trilinear";
  if (v.near_far) name += ", near-far";
  return name;
}

std::string strategy_reason(const std::vector<StrategyAccuracy>& strategies, std::size_t chosen) {
  if (strategies.empty()) return "";
  const StrategyAccuracy& c = strategies[chosen];
  if (strategies.size() == 1) return "the only strategy for this scene (" + errors_text(c) + ")";
  // The next best by the same rule, for scale.
  std::vector<StrategyAccuracy> others;
  for (std::size_t i = 0; i < strategies.size(); ++i)
    if (i != chosen) others.push_back(strategies[i]);
  const StrategyAccuracy& next = others[lowest_error_that_fits(others)];
  std::size_t fitting = 0;
  for (const StrategyAccuracy& s : strategies) fitting += s.fits ? 1 : 0;
  const std::string errors = "wrench " + percent(rendered_error(c)) + "; next: " + strategy_short_name(next.variant) +
                             " " + percent(rendered_error(next));
  if (!c.fits) return "none fits the frame; the lowest error (" + errors + ")";
  return "the lowest error of the " + std::to_string(fitting) + " that fit the frame (" + errors + ")";
}

void RelativeErrors::add(const QueryResult& x, const QueryResult& ref) {
  d[0] += std::pow(x.energy - ref.energy, 2), r[0] += ref.energy * ref.energy;
  d[1] += (x.force - ref.force).squaredNorm(), r[1] += ref.force.squaredNorm();
  d[2] += (x.torque - ref.torque).squaredNorm(), r[2] += ref.torque.squaredNorm();
}

double RelativeErrors::relative(int i) const { return r[i] > 0 ? std::sqrt(d[i] / r[i]) : 0; }

std::vector<Pose> accuracy_poses(const Scene& scene, std::size_t count) {
  const auto& k = scene.trajectory.keyframes;
  if (k.empty() || count == 0) return {scene.part2.pose};
  std::vector<Pose> poses;
  const double t0 = k.front().time_s, t1 = k.back().time_s;
  for (std::size_t i = 0; i < count; ++i)
    poses.push_back(
        trajectory_pose(scene.trajectory, count == 1 ? t1 : t0 + (t1 - t0) * double(i) / double(count - 1)));
  return poses;
}

namespace {

// The exact product's cost at the engine's m': a query at a rotation not yet made, less a
// query at the same rotation again, in ms.
double product_ms(QueryEngine& engine, const Pose& pose) {
  Pose turned = pose;
  turned.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(1e-3, Eigen::Vector3d::UnitZ())) * turned.rotation;
  engine.query(pose);
  const auto t0 = std::chrono::steady_clock::now();
  engine.query(turned);
  const double with_product = seconds_since(t0);
  const auto t1 = std::chrono::steady_clock::now();
  engine.query(turned);
  return 1e3 * std::max(0.0, with_product - seconds_since(t1));
}

// The strategy's errors against the reference at every pose both answer, and how often
// and by how much its error estimate covers the true error.
void compare_with_reference(QueryEngine& engine, const std::vector<Pose>& poses,
                            const std::vector<QueryResult>& reference, StrategyAccuracy& s) {
  RelativeErrors sums;
  std::vector<double> ratios[3];
  std::size_t covered[3] = {0, 0, 0}, compared = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const QueryResult r = engine.query(poses[i]);
    const QueryResult& ref = reference[i];
    if (r.flags != query_ok || ref.flags != query_ok) continue;
    sums.add(r, ref);
    const double truth[3] = {std::abs(r.energy - ref.energy), (r.force - ref.force).norm(),
                             (r.torque - ref.torque).norm()};
    const double estimate[3] = {r.error_estimate.energy, r.error_estimate.force, r.error_estimate.torque};
    ++compared;
    for (int q = 0; q < 3; ++q) {
      if (estimate[q] >= truth[q]) ++covered[q];
      if (truth[q] > 0) ratios[q].push_back(estimate[q] / truth[q]);
    }
  }
  for (int q = 0; q < 3; ++q) {
    s.estimate_coverage[q] = compared ? double(covered[q]) / double(compared) : 0;
    s.estimate_ratio_median[q] = ratios[q].empty() ? 0 : quantile(ratios[q], 0.5);
  }
  s.energy_error = sums.relative(0);
  s.force_error = sums.relative(1);
  s.torque_error = sums.relative(2);
}

}  // namespace

void time_strategy_frame(const QueryTimer& timer, const AccuracyOptions& options, StrategyAccuracy& s) {
  const auto within = [&] { return s.frame_ms_p99 + options.reserved_ms <= options.budget_ms; };
  for (int attempt = 0; attempt < 2; ++attempt) {
    const std::vector<double> times = timer(s.modes, options.repetitions);
    const double p99 = quantile(times, 0.99);
    if (attempt == 0 || p99 < s.frame_ms_p99) {
      s.frame_ms_p50 = quantile(times, 0.5);
      s.frame_ms_p99 = p99;
    }
    if (!s.fits || within()) break;
  }
  s.fits = s.fits && within();
}

AccuracyReport measure_accuracy(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                                const AccuracyOptions& options) {
  const auto note = [&](const std::string& m) {
    if (options.note) options.note(m);
  };
  const auto progress = [&](const std::string& stage, std::uint64_t done, std::uint64_t total) {
    if (options.progress) options.progress(stage, done, total);
  };
  const bool rotation = scene.motion != Motion::translation;
  if (rotation && spectra.part2.deconvolved_width == 0)
    throw Error(
        "accuracy: the spectra have no deconvolved part 2, which the exact-rotation reference needs "
        "(SpectrumOptions::exact_rotation_width > 0 and oversampling >= 2)");
  const QueryVariant base = accuracy_base_variant(scene);

  AccuracyReport report;
  const std::vector<Pose> poses = accuracy_poses(scene, options.poses);
  report.poses = poses.size();

  // The reference: every mode; for 6-DOF the product made for each pose's rotation.
  const auto reference_start = std::chrono::steady_clock::now();
  std::vector<QueryResult> reference;
  {
    const QueryVariant v = rotation ? exact_product(base, ProductUpdate::each_query, spectra.part1.rho.size()) : base;
    auto engine = make_query_engine(ctx, spectra, v);
    engine->set_modes(engine->max_modes());
    report.reference_modes = engine->modes();
    for (std::size_t i = 0; i < poses.size(); ++i) {
      reference.push_back(engine->query(poses[i]));
      progress("reference", i + 1, poses.size());
    }
  }
  report.reference_seconds = seconds_since(reference_start);

  std::vector<QueryVariant> strategies = accuracy_candidates(base, spectra.near != nullptr);
  const std::vector<Pose> timing_poses = tuning_poses(scene);
  for (const QueryVariant& timed : strategies) {
    StrategyAccuracy s;
    s.variant = timed;
    s.name = variant_name(timed);
    auto engine = make_query_engine(ctx, spectra, timed);
    TuneOptions tune;
    tune.repetitions = options.repetitions;
    tune.progress = [&](std::uint64_t done, std::uint64_t total) { progress("tuning " + s.name, done, total); };
    const TuningKey key =
        tuning_key_for(ctx.device.info, timed, spectra, options.budget_ms, options.margin, scene.loop_rate_hz);
    const EngineTuning tuned = tune_engine(*engine, key, timing_poses, tune, options.retune, note);
    const TuningResult beside = tuning_beside_contact(tuned.result, options.reserved_ms);
    s.modes = beside.chosen_modes;
    s.fits = beside.fits;
    time_strategy_frame(engine_query_timer(*engine, timing_poses, scene.loop_rate_hz), options, s);

    // Errors: the interpolated sum as timed; the exact product made for each pose.
    std::unique_ptr<QueryEngine> measured;
    if (timed.rotation == RotationMethod::exact_product) {
      engine.reset();
      QueryVariant each = timed;  // the same strategy, its product (and near part) made for each pose
      each.product_update = ProductUpdate::each_query;
      each.product_modes = s.modes;
      measured = make_query_engine(ctx, spectra, each);
      measured->set_modes(s.modes);
      s.product_ms = product_ms(*measured, poses.front());
    } else {
      measured = std::move(engine);
      measured->set_modes(s.modes);
    }
    compare_with_reference(*measured, poses, reference, s);
    if (timed.rotation == RotationMethod::exact_product && timed.product_update == ProductUpdate::background &&
        !options.turning_deg_per_s.empty()) {
      measured.reset();
      progress("turning " + s.name, 0, 1);
      std::vector<Pose> starts;
      for (std::size_t i = 0; i < poses.size() && starts.size() < 6; i += std::max<std::size_t>(1, poses.size() / 6))
        starts.push_back(poses[i]);
      s.turning = turning_accuracy(ctx, spectra, timed, s.modes, starts, options.turning_deg_per_s, scene.loop_rate_hz);
      progress("turning " + s.name, 1, 1);
    }
    report.strategies.push_back(s);
  }

  report.best = lowest_error_that_fits(report.strategies);
  report.loop = report.best;
  report.why = strategy_reason(report.strategies, report.best);
  return report;
}

}  // namespace snapfit
