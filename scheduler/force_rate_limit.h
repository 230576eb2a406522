#pragma once
// A passive bound on how fast the force sent to the device may change. When part 2 is
// released from a stretched coupling (a peg that rested on a rim while the hand went on
// drops into the hole), the critically damped coupling hands the stored force back at up
// to 2 sqrt(k/m) F per second: a click of several newtons in a few frames. Here the step
// is slowed instead: extra damping of the part's own velocity (relative to part 1) is
// found, only for the frames where the coupling's reaction would otherwise change by more
// than the bound, that keeps the change within it. Damping can only remove energy, so the
// loop stays passive; the released energy is dissipated rather than sent to the hand.
#include <Eigen/Core>

#include "scheduler/virtual_coupling.h"

namespace snapfit {

// The smallest extra damping beta >= 0 (N s/m, added to extra.damping) for which the
// step of step_body moves the coupling's force on the part by at most `max_step` N from
// `last_force` (the force on the part the device felt last frame, N); 0 when the plain
// step already does. Where no beta up to 1e4 m/dt (the part all but stopped) brings the
// step within it (the change comes from the hand, not the part), the beta of the
// smallest step found, possibly 0.
double rate_limiting_damping(const BodyState& part, const BodyState& device, const Wrench& external,
                             const CouplingParams& c, double dt, const ImplicitExtras& extra,
                             const Eigen::Vector3d& last_force, double max_step);

}  // namespace snapfit
