#pragma once
// How much of the engine's wrench the haptic loop can vouch for, from the query's own
// error estimate (snapfit/haptic_loop.h WrenchTrust has the rule).
//
// For one quantity of size v with estimated error e and tolerance a = max(relative v,
// floor), the weight is
//     w = clamp(1 - (e - a) / ((1 - relative) v), 0, 1):
// 1 while e <= a, 0 once e >= a + (1 - relative) v (for a = relative v: once the error
// may be as large as the value), continuous in v and e. Where the relative tolerance
// governs, w > 0 only where e < |F|; if the estimate covers the exact F* (|F* - F| <= e),
// then F.F* >= |F| (|F| - e) > 0: the rendered w F never opposes the exact force. Where
// the floor governs, the force is at most about the floor, which is tolerated anyway.
#include "snapfit/haptic_loop.h"
#include "snapfit/query.h"

namespace snapfit {

// The weight of one quantity (above): its size `value`, its estimated error `error`.
double quantity_trust(double value, double error, double relative, double floor);

// The weight of the whole wrench: the smaller of the force's and the torque's. `wrench`
// and `error` in the loop's units (N, N m: the engine's times the gain). 1 when
// trust.enabled is false.
double wrench_trust(const Wrench& wrench, const ErrorEstimate& error, const WrenchTrust& trust);

}  // namespace snapfit
