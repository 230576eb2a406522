#pragma once
// The near-far split query (QueryVariant::near_far; engine/query/near_field.h): the far
// part by the variant's own sum over part 1's spectrum times G (few modes suffice), plus
// the near part summed in space over part 2's samples. The near part follows the queried
// poses as QueryVariant::product_update says: each_query evaluates it at every pose;
// background evaluates it on a worker thread at the latest pose queried, and each frame
// renders it to first order about the pose it was made at,
//   E_near(t, R) = E0 - F0.(t - t0) - T0.theta,  R = exp([theta]x) R0,
// with F0 and J_l(theta)^-T T0 its exact force and torque, so the rendered wrench stays
// the gradient of the rendered energy (include/snapfit/query.h). Its error estimate adds
// how far the last first-order part was from the next evaluation (the staleness); until
// the worker's first evaluation (milliseconds), a query returns the far part alone with an
// error estimate as large as it.
#include <memory>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

// Throws snapfit::Error for a translation-only variant, spectra without a near field
// (pipeline/assembly_pair.h PairOptions::near_field), or what the far part's engine throws.
std::unique_ptr<QueryEngine> make_split_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                              const QueryVariant& variant,
                                              const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
