#pragma once
// Per-pose queries (Behandish & Ilies 2016 eq. 10-12; docs/design.md "Correlation in the Fourier
// domain"): for part 2 at pose (R, t) relative to part 1, with w' = -R^T w_k,
//     f(R, t)     = sum_k rho1^(w_k) rho2^(w') exp(2 pi i w_k.tau) dw,  tau = t + R c2 - c1
//     df/dt       = sum_k (2 pi i w_k) [same term]
//     df/dtheta   = the same sum's derivative under R -> exp(theta [e]x) R: through w'
//                   (the gradient of rho2^ at w', crossed with w') and through R c2
// over the m' retained modes (a low-pass ball: the modes with the smallest |w|, in
// order, so m' changes without recompiling or re-uploading), with rho2^ at w' either
// interpolated from the oversampled spectrum or exact (RotationMethod). Energy E = -Re f,
// force F = -dE/dt = Re df/dt, torque T = -dE/dtheta = Re df/dtheta, all in part 1's
// frame, the torque about part 2's reference point (its frame origin): F and T are the
// derivatives of the E the same query returns.
#include <Eigen/Core>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "snapfit/pose.h"

namespace snapfit {

enum class Interpolation {
  trilinear,  // 8 taps per mode (Behandish & Ilies 2016)
  tricubic,   // Catmull-Rom, 64 taps per mode
};

// How a 6-DOF query follows part 2's rotation.
enum class RotationMethod {
  // Part 2's stored spectrum interpolated at the rotated frequencies, every retained mode
  // every frame (Behandish & Ilies 2016); torque from the gradient of the same interpolant.
  interpolated,
  // The pair's product spectrum computed exactly (to ~1e-6) for a rotation R0, with its
  // rotation derivative, then summed along x-lines like a translation-only query, to
  // first order in the rotation since R0: far more modes per frame, exact at R0.
  exact_product,
};

// When an exact_product engine remakes its product for the current rotation.
enum class ProductUpdate {
  each_query,  // before any query whose rotation is not R0: exact at every pose (tens of ms per new rotation)
  background,  // on a worker thread that follows the poses queried (the haptic loop's: a frame never waits)
};

struct QueryVariant {
  bool force = true;
  bool torque = true;             // T = -dE/dtheta of the same energy (include/snapfit/query.h)
  bool translation_only = false;  // R fixed at the identity: no interpolation at all
  // The trilinear slope jumps at the spectrum's nodes, where an aligned pose (R = I)
  // puts every rotated frequency: its torque there is a one-sided slope. Catmull-Rom's
  // slope is continuous (what snapfit run and the pipeline's query_variant_for use).
  Interpolation interpolation = Interpolation::trilinear;
  // Store the 6-DOF spectrum cube as half floats (scaled per spectrum): half the bytes
  // per tap (a smaller cache footprint at large m'). Adds about 1e-5 relative to the
  // float cube's results (tests/test_pose_query.cpp measures it, bound 5e-5): below the
  // interpolation error of both schemes at oversampling 2. Ignored for translation only.
  bool half_cube = false;
  // When both parts' samples are real or both imaginary (the affinity i * rho always
  // is), the terms at w and -w are complex conjugates, so each retained pair is
  // evaluated once with twice the weight: half the work for the same m' and the same
  // result (Re f, F, T; Im f is 0 for every complete pair). False sums every mode (for
  // checks).
  bool fold_conjugate_pairs = true;
  RotationMethod rotation = RotationMethod::interpolated;    // 6-DOF only
  ProductUpdate product_update = ProductUpdate::each_query;  // exact_product only
  // exact_product: the most modes an engine can sum, its max_modes() (0: every mode). A
  // product costs time in proportion to the m' in use, its buffers memory in proportion
  // to this.
  std::size_t product_modes = 0;
  // Split the sum as Ewald summation splits one (docs/design.md "Near and far"): this
  // variant's sum over part 1's spectrum smoothed by a Gaussian (the far part, which needs
  // few modes), plus the rest summed exactly in space over part 2's samples (the near
  // part), made before each query or on a worker thread that follows the queried poses as
  // product_update says. Needs spectra made with a near field (6-DOF, grid sources).
  bool near_far = false;
};

// Names and enums, one table each, shared by the scene reader, the tool, the JSON and
// text writers and the Python module.
const char* interpolation_name(Interpolation interpolation);  // "trilinear", "tricubic"
std::optional<Interpolation> interpolation_named(const std::string& name);

// The query strategies a user picks by name: the rotated spectrum interpolated
// ("tricubic", "trilinear"), the exact product ("exact-product"), or its near-far split
// ("near-far").
enum class QueryStrategy { tricubic, trilinear, exact_product, near_far };
const std::vector<QueryStrategy>& query_strategies();  // in that order
const char* strategy_name(QueryStrategy strategy);
std::optional<QueryStrategy> strategy_named(const std::string& name);
// `base` (a scene's variant) made to render `strategy`, the exact product remade as
// `update` says. A translation-only variant has only its lines: returned as it is.
QueryVariant with_strategy(QueryVariant base, QueryStrategy strategy, ProductUpdate update);

// The variant in words: "6dof energy force torque tricubic", "translation energy force",
// "6dof energy force torque exact-product background", ... (tuning files and reports).
std::string variant_name(const QueryVariant& variant);

enum QueryFlags : std::uint32_t {
  query_ok = 0,
  query_outside_grid = 1u << 0,  // part 2 beyond the padded box: the result would alias; zero returned
  query_bad_pose = 1u << 1,      // non-finite or non-unit rotation input: zero returned
};

// An estimate of the absolute error of a query's energy, |force| and |torque| error
// against the untruncated sum with exact rotation: kErrorEstimateScale times the root
// sum of squares of the two octave bands below the cut, modes (m'/4, m'/2] and
// (m'/2, m'] (docs/design.md "Error estimate").
struct ErrorEstimate {
  double energy = 0, force = 0, torque = 0;
};

struct QueryResult {
  double energy = 0;
  Eigen::Vector3d force = Eigen::Vector3d::Zero();
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();
  std::complex<double> score = 0;  // f(R, t)
  ErrorEstimate error_estimate;
  std::uint32_t flags = query_ok;
  std::size_t modes = 0;  // m' used
  double seconds = 0;     // wall time of this query (batch: of the whole batch / count)
  // A constraint hybrid's (Method::vps_hybrid) engaged constraint of largest weight:
  // 0 none, 1 concentric, 2 planar, and its blend weight x in [0, 1]; 0 for other methods.
  std::uint8_t constraint = 0;
  double constraint_weight = 0;
};

// The per-frame engine of an assembly pair on one device. Two implementations: the
// 6-DOF sum over interpolated, rotated spectra and the translation-only sum over
// x-line intervals (part 2 never rotates). Make one with snapfit::Assembly.
class QueryEngine {
 public:
  virtual ~QueryEngine() = default;

  virtual const QueryVariant& variant() const = 0;
  virtual std::size_t max_modes() const = 0;  // every mode of the FFT grid, by increasing |w|
  virtual std::size_t modes() const = 0;      // m'
  // Terms the kernel evaluates per query at the current m': about m' / 2 with conjugate
  // pairs folded (QueryVariant::fold_conjugate_pairs), else m'.
  virtual std::size_t evaluated_terms() const = 0;
  // Clamped to [1, max_modes()]. May allocate and upload; call it outside the frame.
  virtual void set_modes(std::size_t m) = 0;
  // m' for the frames to come, from a loop that must not wait: as set_modes, except that
  // an engine whose larger m' needs work of its background thread (the exact rotation's
  // product made for more modes) keeps the m' it has until that work is done, and takes
  // the new one at the first query after; modes() and each result's `modes` say which is
  // in use.
  virtual void request_modes(std::size_t m) { set_modes(m); }

  // One pose: no heap allocation once set_modes has run (the haptic frame's path).
  virtual QueryResult query(const Pose& pose) = 0;
  // `count` poses in one launch into results[0 .. count). Allocates only when the batch
  // is larger than every batch before it.
  virtual void query_batch(const Pose* poses, std::size_t count, QueryResult* results) = 0;
  std::vector<QueryResult> query_batch(const std::vector<Pose>& poses) {
    std::vector<QueryResult> results(poses.size());
    query_batch(poses.data(), poses.size(), results.data());
    return results;
  }
};

}  // namespace snapfit
