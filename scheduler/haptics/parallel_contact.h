#pragma once
// The rigid contact evaluated on several threads. Near a tight fit every sample point of a
// face that touches part 1 lies within the contact's reach and must be looked up each
// frame (27,000 on the three-peg pair): more than one core can do within a frame's
// budget. The points' chunks are dealt out to the calling thread and helper threads that
// live as long as the evaluator; a frame wakes them, each sums its share, the caller adds
// the shares up. No heap allocation per evaluation.
#include <functional>
#include <memory>

#include "scheduler/haptics/rigid_contact.h"

namespace snapfit {

// Threads worth using for `model` on this machine: 1 below 16,384 sample points (waking
// helpers costs more than it saves), else the machine's hardware threads, at most
// `max_threads` (0: at most 4).
unsigned contact_threads_for(const RigidContactModel& model, unsigned max_threads = 0);

// A share of the contact's sum, as contact_wrench_share computes it.
using ContactShareFunction = ContactWrench (*)(const RigidContactModel&, const Pose&, std::size_t share,
                                               std::size_t shares);

// The loop's view of a model (LoopConfig::contact), on `threads` threads (0: as
// contact_threads_for says); it keeps the model and its helper threads alive and is not
// to be called from two threads at once. `share` computes the shares (another
// evaluation of the same sum, for a benchmark's reference).
std::function<ContactWrench(const Pose&)> contact_evaluator(std::shared_ptr<const RigidContactModel> model,
                                                            unsigned threads = 0,
                                                            ContactShareFunction share = contact_wrench_share);

}  // namespace snapfit
