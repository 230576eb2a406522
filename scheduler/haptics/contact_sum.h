#pragma once
// The rigid contact's sums over its penetrating points (scheduler/haptics/rigid_contact.h), in
// double, as one array of terms: the energy, the wrench and the Gauss-Newton stiffness's
// 21 distinct entries, each point adding its products directly (a 6x6 rank update
// through Eigen costs several times more for one point).
#include <algorithm>
#include <cstddef>

#include "snapfit/haptic_loop.h"

namespace snapfit {

// term[]: energy (J), force (3, N), torque (3, N m), the stiffness's lower triangle row
// by row: (0,0), (1,0), (1,1), (2,0), ...
constexpr int kContactTerms = 28;
constexpr int kForceTerm = 1, kTorqueTerm = 4, kStiffnessTerm = 7;

struct ContactSum {
  double term[kContactTerms] = {};
  std::size_t points = 0;
  double depth = 0;  // the deepest point's -phi, scene units

  // One point's term: k_a = k A (N / m per m of depth), phi_m its depth past the skin in
  // metres (< 0), j = (dphi/dt, dphi/dtheta in metres per radian), phi its signed
  // distance (scene units).
  void add(double k_a, double phi_m, const double j[6], double phi) {
    term[0] += 0.5 * k_a * phi_m * phi_m;
    for (int a = 0; a < 6; ++a) term[kForceTerm + a] -= k_a * phi_m * j[a];
    int n = kStiffnessTerm;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c <= r; ++c) term[n++] += k_a * j[r] * j[c];
    ++points;
    depth = std::max(depth, -phi);
  }

  // Into a ContactWrench, the stiffness's lower triangle only (as contact_wrench_share gives it).
  ContactWrench wrench() const {
    ContactWrench c;
    c.energy_j = term[0];
    for (int a = 0; a < 3; ++a) c.wrench.force[a] = term[kForceTerm + a], c.wrench.torque[a] = term[kTorqueTerm + a];
    int n = kStiffnessTerm;
    for (int r = 0; r < 6; ++r)
      for (int col = 0; col <= r; ++col) c.stiffness(r, col) = term[n++];
    c.points = points;
    c.depth = depth;
    return c;
  }
};

}  // namespace snapfit
