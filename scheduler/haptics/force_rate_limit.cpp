#include "scheduler/haptics/force_rate_limit.h"

#include <algorithm>
#include <cmath>

namespace snapfit {

double rate_limiting_damping(const BodyState& part, const BodyState& device, const Wrench& external,
                             const CouplingParams& c, double dt, const ImplicitExtras& extra,
                             const Eigen::Vector3d& last_force, double max_step) {
  if (!(max_step > 0)) return 0;
  const auto step_with = [&](double beta) {
    BodyState trial = part;
    ImplicitExtras e = extra;
    e.damping += beta;
    step_body(trial, device, external, c, dt, e);
    return (coupling_wrench(trial, device, c).force - last_force).norm();
  };
  const double plain = step_with(0);
  if (!(plain > max_step)) return 0;
  // The step is not monotone in beta: damping first keeps the part's velocity (and so the
  // damper's share of the force) near last frame's, then stops the part, which changes
  // the force again. So scan beta upwards in factors of 2 from 1e-3 m/dt to 1e4 m/dt
  // (where the part all but stops) for the first value within the bound, then bisect
  // between it and the one before; none within it: the beta of the smallest step.
  const double unit = c.mass_kg / dt;
  // The smallest beta in (lo, hi] within the bound, given step(lo) > max_step >= step(hi).
  const auto smallest_within = [&](double lo, double hi) {
    for (int i = 0; i < 20 && hi - lo > 1e-3 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (step_with(mid) <= max_step ? hi : lo) = mid;
    }
    return hi;
  };
  double below = 0, best = 0, best_step = plain;
  for (double beta = 1e-3 * unit; beta <= 1e4 * unit; beta *= 2) {
    const double step = step_with(beta);
    if (step <= max_step) return smallest_within(below, beta);
    if (step < best_step) best = beta, best_step = step;
    below = beta;
  }
  if (best == 0) return 0;  // damping the part only makes it worse: the change is the hand's
  // The valley may lie between the scan's points: its bottom by golden-section search on
  // log(beta) over the best point's neighbours.
  const double g = 0.5 * (std::sqrt(5.0) - 1);
  double a = std::log(0.5 * best), b = std::log(2 * best);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double f1 = step_with(std::exp(x1)), f2 = step_with(std::exp(x2));
  for (int i = 0; i < 24; ++i) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = step_with(std::exp(x1));
    } else {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = step_with(std::exp(x2));
    }
  }
  const double bottom = std::exp(f1 < f2 ? x1 : x2);
  if (std::min(f1, f2) <= max_step) return smallest_within(0.5 * best, bottom);
  return std::min(f1, f2) < best_step ? bottom : best;
}

Eigen::Vector3d slewed_sent_force(SentForceSlew& slew, const Eigen::Vector3d& coupling_force,
                                  const Eigen::Vector3d& hand_m, double max_step, double dissipated_j) {
  if (!slew.started) {
    slew.started = true;
    slew.last_hand = hand_m;
    slew.last_sent = coupling_force;
    return coupling_force;
  }
  // The work last frame's offset did on the hand while it moved.
  const Eigen::Vector3d hand_step = hand_m - slew.last_hand;
  const double work = slew.last_offset.dot(hand_step);
  slew.tank_j = std::min(slew.capacity_j, slew.tank_j + std::max(dissipated_j, 0.0)) - work;
  slew.spent_j += work;
  slew.last_hand = hand_m;
  slew.last_hand_step = hand_step;

  Eigen::Vector3d sent = coupling_force;
  const Eigen::Vector3d change = coupling_force - slew.last_sent;
  if (max_step > 0 && change.norm() > max_step) {
    const Eigen::Vector3d slewed = slew.last_sent + change * (max_step / change.norm());
    const Eigen::Vector3d offset = slewed - coupling_force;
    // The hand's next displacement is not known yet: estimate it by the last one, with
    // a margin of 2 (and 1 um at least, for a hand at rest that starts moving).
    const double reach = std::max(2 * slew.last_hand_step.norm(), 1e-6);
    if (slew.tank_j >= offset.norm() * reach) {
      sent = slewed;
      ++slew.slewed_frames;
    }
  }
  slew.last_offset = sent - coupling_force;
  slew.last_sent = sent;
  return sent;
}

}  // namespace snapfit
