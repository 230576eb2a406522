#pragma once
// The per-frame query engine of a pair of spectra on one device: the 6-DOF sum
// (engine/query/six_dof_query.h) or, for a variant with translation_only, the sum over x-line
// intervals (engine/query/translation_query.h), behind include/snapfit/query.h's QueryEngine.
#include <memory>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

// Uploads what the variant needs and builds its kernel. The engine keeps its own
// handles to the device (it may outlive `ctx`). Throws snapfit::Error when the variant
// needs torque spectra that are missing, asks torque of a translation-only query, or
// the device fails.
std::unique_ptr<QueryEngine> make_query_engine(const ComputeContext& ctx, const PairSpectra& spectra,
                                               const QueryVariant& variant,
                                               const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
