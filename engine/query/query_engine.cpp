#include "engine/query/query_engine.h"

#include <string>

#include "engine/query/rotated_product_query.h"
#include "engine/query/split_query.h"
#include "engine/query/six_dof_query.h"
#include "engine/query/translation_query.h"
#include "snapfit/error.h"

namespace snapfit {

std::unique_ptr<QueryEngine> make_query_engine(const ComputeContext& ctx, const PairSpectra& spectra,
                                               const QueryVariant& variant, const ProgramCacheConfig& cache) {
  for (std::size_t n : spectra.dims)
    if (n > 65534)
      throw Error("FFT grid axis of " + std::to_string(n) + " points is beyond the query kernel's 16-bit mode indices");
  if (variant.near_far) return make_split_query(ctx, spectra, variant, cache);
  if (variant.translation_only) return make_translation_query(ctx, spectra, variant, cache);
  if (variant.rotation == RotationMethod::exact_product)
    return make_rotated_product_query(ctx, spectra, variant, cache);
  return make_six_dof_query(ctx, spectra, variant, cache);
}

}  // namespace snapfit
