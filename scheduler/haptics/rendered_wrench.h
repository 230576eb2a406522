#pragma once
// The wrench the loop renders at a pose (the engine's times the gain, plus the rigid
// contact) and its potential: where it rests (a descent from a pose), and what the user
// feels there (its stiffness by one-sided differences along each direction of part 1's
// frame, beside the coupling's).
#include <array>
#include <cstdint>
#include <functional>

#include "snapfit/haptic_loop.h"
#include "snapfit/job_facts.h"  // RenderedStiffness
#include "snapfit/pose.h"

namespace snapfit {

// The rendered wrench (N, N m) and potential (J) at `pose`: gain * E * metres_per_unit
// plus the contact's; `flags` are the engine's.
struct RenderedWrench {
  Wrench wrench;
  double potential_j = 0;
  std::uint32_t flags = 0;
  ContactWrench contact;
};
RenderedWrench rendered_wrench(const WrenchEvaluator& engine, double geometry_gain,
                               const std::function<ContactWrench(const Pose&)>& contact, double metres_per_unit,
                               const Pose& pose);

// The local minimum of the rendered potential reached from `start` by damped Newton
// steps (the contact's stiffness plus `regularisation` N/m and N m/rad on the diagonal),
// each accepted only where the potential falls; stops when a step is below 1e-6 scene
// units and 1e-6 rad, or after `max_steps`.
struct RestPoint {
  Pose pose;
  double potential_j = 0;
  int steps = 0;
};
RestPoint descend_rendered(const WrenchEvaluator& engine, double geometry_gain,
                           const std::function<ContactWrench(const Pose&)>& contact, const CouplingParams& coupling,
                           const Pose& start, int max_steps = 400);

// At `pose`, with the loop's evaluator, gain and contact (null: none) and coupling.
RenderedStiffness rendered_stiffness(const WrenchEvaluator& engine, double geometry_gain,
                                     const std::function<ContactWrench(const Pose&)>& contact,
                                     const CouplingParams& coupling, const Pose& pose);

}  // namespace snapfit
