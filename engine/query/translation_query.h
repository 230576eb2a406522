#pragma once
// The translation-only query (kernels/pose_query.cl translation_lines): part 2 never
// rotates, so the product W_k = S1(w_k) S2(-w_k) dw is precomputed and each query sums
// W_k e^{2 pi i w_k.tau} over the x-line intervals that hold the first m' modes
// (engine/query/translation_lines.h). No interpolation, no torque.
#include <memory>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

// Throws snapfit::Error for a variant with torque, or when the device fails.
std::unique_ptr<QueryEngine> make_translation_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                                    const QueryVariant& variant,
                                                    const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
