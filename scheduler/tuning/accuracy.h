#pragma once
// What a frame budget buys for a scene (`snapfit accuracy`, perf/bench_accuracy): each
// query strategy tuned for the budget on a device (scheduler/tuning/engine_tuning.h), its
// per-frame time, and its error against a reference that is exact in rotation: every
// mode of the exact-rotation product (engine/query/rotated_product_query.h), made for each
// pose's own rotation, at poses along the scene's trajectory. The reference equals a
// double-precision sum over the DTFT of part 2's samples (tests/test_exact_rotation.cpp)
// and, at lattice poses, the direct sum over the meshes (tests/test_direct_reference.cpp).
//
// Error of a quantity x over the poses: sqrt(sum |x - x_ref|^2) / sqrt(sum |x_ref|^2).
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/spectra/spectra.h"
#include "scheduler/modes/mode_tuning.h"
#include "snapfit/accuracy.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

// The error measure above, accumulated pose by pose: relative(0) energy, 1 force, 2 torque.
struct RelativeErrors {
  double d[3] = {0, 0, 0}, r[3] = {0, 0, 0};
  void add(const QueryResult& x, const QueryResult& ref);
  double relative(int i) const;
};

struct AccuracyOptions {
  double budget_ms = 1.0;
  double margin = 0.25;  // TuneOptions::margin
  // The frame's time other work takes beside the query (the loop's rigid contact, ms):
  // each strategy's m' is the one that fits beside it (tuning_beside_contact), so the
  // errors measured are those of the m' the loop renders.
  double reserved_ms = 0;
  std::size_t poses = 24;  // reference poses, evenly in time along the trajectory
  bool retune = false;     // measure even when the tuning file matches
  std::size_t repetitions = 400;
  // Angular speeds (deg/s) at which the exact product with background updates is also
  // measured while part 2 turns (TurningAccuracy); none: only at rest.
  std::vector<double> turning_deg_per_s;
  std::function<void(const std::string& stage, std::uint64_t done, std::uint64_t total)> progress;
  std::function<void(const std::string&)> note;
};

// The loop's variant of `scene` the strategies start from: energy and force, the torque
// when the scene turns and asks for it, tricubic interpolation.
QueryVariant accuracy_base_variant(const Scene& scene);

// The strategies measured for a scene whose loop variant is `base` (6-DOF: the
// interpolated sum with base's interpolation, the same trilinear, the exact product
// with background updates over every mode and, when the spectra have a near field, the
// same split into near and far parts; translation-only: the translation lines).
std::vector<QueryVariant> accuracy_candidates(const QueryVariant& base, bool near_field = false);

// The error of what the loop renders: the larger relative error of force and torque
// (of those the variant computes; the energy's when it computes neither).
double rendered_error(const StrategyAccuracy& s);

// The index of the strategy with the lowest rendered_error among those that fit the
// frame (among all when none fits); the first on a tie. strategies must not be empty.
std::size_t lowest_error_that_fits(const std::vector<StrategyAccuracy>& strategies);

// Why the chosen strategy, in a few words: the rule it won by and its rendered error against
// the next best's (the comparison itself is the strategies' table).
std::string strategy_reason(const std::vector<StrategyAccuracy>& strategies, std::size_t chosen);

// Times `s`'s frame at s.modes with `timer` (the loop's pacing) into s.frame_ms_p50/p99;
// s.fits stays true only when the tuner said so (s.fits on entry) and the p99 beside
// options.reserved_ms is within options.budget_ms. A p99 over the budget is timed once more
// and the lower kept, as the tuner does with its levels: a burst of other work on the
// machine only adds time, and one burst should not rule a strategy out for later runs.
void time_strategy_frame(const QueryTimer& timer, const AccuracyOptions& options, StrategyAccuracy& s);

// The poses the reference is computed at: the scene's trajectory at `count` evenly spaced
// times (both ends included), else part 2's scene pose.
std::vector<Pose> accuracy_poses(const Scene& scene, std::size_t count);

// Tunes and measures each strategy the scene allows on ctx's device
// (accuracy_candidates of the scene's tricubic variant) and picks the best. Throws snapfit::Error when the spectra
// cannot carry a strategy's reference (no deconvolved spectrum for a 6-DOF scene) or the device fails.
AccuracyReport measure_accuracy(const ComputeContext& ctx, const Scene& scene, const PairSpectra& spectra,
                                const AccuracyOptions& options);

}  // namespace snapfit
