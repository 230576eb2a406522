#pragma once
// Per-pose queries (seed 000 eq. 10-12; DESIGN.md): for part 2 at pose (R, t) relative
// to part 1, with w' = -R^T w_k,
//     f(R, t)     = sum_k rho1^(w_k) rho2^(w') exp(2 pi i w_k.t) dw          (score)
//     df/dt       = sum_k (2 pi i w_k) [same term]
//     df/dtheta   = R sum_k (2 pi i) (w' x Q2^(w')) rho1^(w_k) exp(2 pi i w_k.t) dw
// over the m' retained modes (a low-pass ball: the modes with the smallest |w|, in
// order, so m' changes without recompiling or re-uploading), with rho2^ and Q2^
// interpolated at w' from the oversampled spectrum. Energy E = -Re f, force
// F = -dE/dt = Re df/dt, torque T = -dE/dtheta = Re df/dtheta, all in part 1's frame,
// the torque about part 2's reference point (its frame origin), for a rotation
// increment applied on the left: R -> exp(theta [e]x) R.
#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <vector>

#include "snapfit/pose.h"
#include "engine/program_cache.h"
#include "engine/spectra.h"

namespace snapfit {

enum class Interpolation {
  trilinear,  // 8 taps per mode (seed 000)
  tricubic,   // Catmull-Rom, 64 taps per mode
};

struct QueryVariant {
  bool force = true;
  bool torque = true;                 // needs spectra with torque
  bool translation_only = false;      // R fixed at the identity: no interpolation at all
  Interpolation interpolation = Interpolation::trilinear;
  // Store the 6-DOF spectrum cube as half floats (scaled per spectrum): half the bytes
  // per tap (a smaller cache footprint at large m'). Adds about 1e-5 relative to the
  // float cube's results (tests/test_pose_query.cpp measures it, bound 5e-5): below the
  // interpolation error of both schemes at oversampling 2. Ignored for translation only.
  bool half_cube = false;
  // When both parts' samples are real or both imaginary (the affinity i * rho always is:
  // PairSpectra::conjugate_pairs), the 6-DOF terms at w and -w are complex conjugates, so
  // each retained pair is evaluated once with twice the weight: half the work for the
  // same m' and the same result (Re f, F, T; Im f is 0 for every complete pair). False
  // sums every mode (for checks). Translation-only queries fold the same way, over half
  // of their x-lines (engine/translation_lines.h).
  bool fold_conjugate_pairs = true;
};

enum QueryFlags : std::uint32_t {
  query_ok = 0,
  query_outside_grid = 1u << 0,  // part 2 beyond the padded box: the result would alias; zero returned
  query_bad_pose = 1u << 1,      // non-finite or non-unit rotation input: zero returned
};

struct QueryResult {
  double energy = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  std::complex<double> score = 0;  // f(R, t)
  std::uint32_t flags = query_ok;
  std::size_t modes = 0;           // m' used
  double seconds = 0;              // wall time of this query (batch: of the whole batch / count)
};

class PoseQueryEngine {
 public:
  // Uploads the spectra and builds the kernel variant. Throws snapfit::Error when the
  // variant needs torque spectra that are missing, or the device fails.
  PoseQueryEngine(const ComputeContext& ctx, const PairSpectra& spectra, QueryVariant variant,
                  const ProgramCacheConfig& cache = default_program_cache());
  ~PoseQueryEngine();
  PoseQueryEngine(const PoseQueryEngine&) = delete;
  PoseQueryEngine& operator=(const PoseQueryEngine&) = delete;

  std::size_t max_modes() const;  // every mode of the FFT grid, by increasing |w|
  std::size_t modes() const;
  // Terms the kernel evaluates per query at the current m': m' with conjugate pairs
  // folded (about m' / 2, see QueryVariant::fold_conjugate_pairs), else m'. Translation
  // only: the nodes of the selected line intervals plus its extra single terms.
  std::size_t evaluated_terms() const;
  void set_modes(std::size_t m);  // clamped to [1, max_modes()]

  QueryResult query(const Pose& pose);
  std::vector<QueryResult> query_batch(const std::vector<Pose>& poses);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace snapfit
