#pragma once
// A reference for energy, force and torque that does not interpolate in rotation: part 1's
// affinity samples rho1(p) on its grid against part 2's affinity evaluated directly from
// its mesh (engine/fields/descriptors.h descriptors_at_points) at the moved points
// q = R^T (p - t) of part 1's lattice, summed in double (seed 000 eq. 7 as a Riemann sum
// on part 1's lattice):
//     f(R, t) = h^3 sum_p rho1(p) rho2(R^T (p - t)),   E = -Re f,
// over the p whose q lies in part 2's sampled box (grown by half a spacing; outside it
// rho2 is 0, as in the spectra). F = -dE/dt and T = -dE/dtheta (about part 2's origin,
// R -> exp(theta [e]x) R) are central differences of E.
//
// At a pose that maps part 1's lattice onto part 2's (R = I or a lattice rotation such as
// a half turn about an axis, t = o1 - R o2 + h n), q are part 2's grid points and f equals
// the untruncated spectral sum of the sampled fields: tests/test_direct_reference.cpp.
// Elsewhere the two differ by how the sampled spectrum represents part 2 between samples.
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/fields/descriptors.h"
#include "mesh/mesh.h"
#include "snapfit/query.h"

namespace snapfit {

struct DirectReferenceOptions {
  double translation_step = 0;  // central-difference step for F, scene units (0: half a grid spacing)
  double rotation_step = 0;     // for T, radians (0: half a grid spacing at part 2's farthest sample)
  bool force = true;
  bool torque = true;
  DescriptorOptions descriptors;  // for part 2's values at the moved points
};

class DirectReference {
 public:
  // part1: part 1's fields on its grid; part2_mesh and part2_grid: part 2's mesh and the
  // grid its fields were sampled on (its box, spacing and unit frame). Both parts share
  // the descriptor parameters of part1.params.
  DirectReference(const ComputeContext& ctx, const DescriptorFields& part1, const Mesh& part2_mesh,
                  const GridSpec& part2_grid, const DirectReferenceOptions& options = {});

  // E, F and T at every pose (one descriptor evaluation for all of them); a non-finite or
  // non-unit rotation is flagged query_bad_pose with zeros.
  std::vector<QueryResult> evaluate(const std::vector<Pose>& poses) const;

  double translation_step() const { return translation_step_; }
  double rotation_step() const { return rotation_step_; }

 private:
  const ComputeContext& ctx_;
  const DescriptorFields& part1_;
  std::vector<float> rho1_;  // a1 = Im rho1 (skeletal) or rho1 (indicator), part 1's grid order
  const Mesh& part2_mesh_;
  GridSpec part2_grid_;
  DirectReferenceOptions options_;
  double translation_step_ = 0, rotation_step_ = 0;
};

}  // namespace snapfit
