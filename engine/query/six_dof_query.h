#pragma once
// The 6-DOF query (kernels/pose_query.cl pose_query): part 2's spectra interpolated at
// the rotated frequencies w' = -R^T w_k, summed over the m' lowest-|w| modes with
// conjugate pairs folded (include/snapfit/query.h has the formulas and frames).
#include <memory>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

// Uploads the mode records and builds the kernel variant. Throws snapfit::Error when the
// variant needs torque spectra that are missing, or the device fails.
std::unique_ptr<QueryEngine> make_six_dof_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                                const QueryVariant& variant,
                                                const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
