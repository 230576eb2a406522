#pragma once
// The collision predicate on the truncated Fourier sum (Behandish & Ilies 2015 sec. 4.1,
// docs/spheres.md). With indicator affinities a query's energy is the overlap volume
// g(R, t) of the two parts summed over the m' retained modes. The truncated sum g_m'
// differs from the sum over every mode by at most
//     B(m') = dw sqrt(sum_{k >= m'} |S1(w_k)|^2) sqrt(sum_{k >= m'} |S2(w_k)|^2)   (Cauchy-Schwarz)
// over the retained modes' order (a low-pass ball), so g_m' > B(m') proves that the parts
// overlap; below it the truncated sum cannot tell a touch from a small overlap.
//
//   snapfit::Assembly assembly(snapfit::indicator_scene(snapfit::load_scene(path)));
//   auto engine = assembly.make_query_engine();
//   const snapfit::TruncationTails tails = snapfit::truncation_tails(assembly);
//   const snapfit::CollisionVerdict v = snapfit::collision_verdict(engine->query(pose), tails);
#include <cstddef>
#include <vector>

#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

class Assembly;

// The scene with the indicator descriptor (Behandish & Ilies 2016 eq. 1): its query
// energy is the overlap volume of the two parts.
Scene indicator_scene(const Scene& scene);

// The tails of both parts' spectra along the query engine's mode order.
struct TruncationTails {
  std::vector<double> tail1, tail2;  // tail_i[m] = sum over the modes after the first m of |S_i|^2 (size modes + 1)
  double dw = 0;                     // 1 / (L_x L_y L_z)
  // B(m'): the bound on |g - g_m'| (scene units^3); 0 at m' = every mode.
  double bound(std::size_t modes) const;
};

// The tails of an assembly's spectra (of an indicator scene for the verdict to hold).
TruncationTails truncation_tails(const Assembly& assembly);

struct CollisionVerdict {
  bool collides = false;  // proven overlap; false means unknown, not free
  double overlap = 0;     // g_m', the truncated overlap volume (the query's energy)
  double bound = 0;       // B(m')
};

// The verdict for a query of an indicator pair (the energy is the overlap volume).
CollisionVerdict collision_verdict(const QueryResult& result, const TruncationTails& tails);

}  // namespace snapfit
