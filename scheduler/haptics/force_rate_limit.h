#pragma once
// A passive bound on how fast the force sent to the device may change. When part 2 is
// released from a stretched coupling (a peg that rested on a rim while the hand went on
// drops into the hole), the critically damped coupling hands the stored force back at up
// to 2 sqrt(k/m) F per second: a click of several newtons in a few frames. Here the step
// is slowed instead: extra damping of the part's own velocity (relative to part 1) is
// found, only for the frames where the coupling's reaction would otherwise change by more
// than the bound, that keeps the change within it. Damping can only remove energy, so the
// loop stays passive; the released energy is dissipated rather than sent to the hand.
//
// Damping cannot help where the change comes from the part being stopped or released by
// the contact within a frame (a peg sliding off a rim drops; the wall stops it): slowing
// that would take energy. For those frames the sent force itself is slewed towards the
// coupling's at the bound, and the energy that this difference does on the hand is paid
// from a tank that only the bound's damping fills (the energy-tank practice of Franken
// et al. 2011, "Bilateral telemanipulation with time delays: a two-layer approach"): what
// the hand receives beyond the passive coupling's never exceeds what damping removed.
#include <Eigen/Core>

#include "scheduler/haptics/virtual_coupling.h"

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

// The sent force's slew stage. The force the hand feels is the coupling's reaction,
// except that it moves by at most `max_step` a frame while the tank can pay for the
// difference. Plain data; no heap.
struct SentForceSlew {
  Eigen::Vector3d last_sent = Eigen::Vector3d::Zero();   // N, force sent last frame
  Eigen::Vector3d last_offset = Eigen::Vector3d::Zero(); // N, sent minus the coupling's, last frame
  Eigen::Vector3d last_hand = Eigen::Vector3d::Zero();   // m, the hand's position last frame
  Eigen::Vector3d last_hand_step = Eigen::Vector3d::Zero();  // m, the hand's last displacement
  bool started = false;
  double tank_j = 0;      // energy available to the slew, J
  double capacity_j = 0;  // the tank's bound, J: energy stored long ago is not spent in one go
  std::size_t slewed_frames = 0;
  double spent_j = 0;  // energy the offset did on the hand, J (net; negative when it took energy)
};

// The force to send this frame, given the coupling's reaction `coupling_force` (N, on the
// hand), the hand's position `hand_m` (m), `max_step` (N) and the energy `dissipated_j`
// that the bound's damping removed this frame (added to the tank). The offset sent last
// frame is first charged for the work it did over the hand's displacement since; an
// offset is sent only while the tank covers its estimated work (at the last
// displacement, twice over); otherwise the coupling's force goes out unchanged.
Eigen::Vector3d slewed_sent_force(SentForceSlew& slew, const Eigen::Vector3d& coupling_force,
                                  const Eigen::Vector3d& hand_m, double max_step, double dissipated_j);

}  // namespace snapfit
