#pragma once
// The score for every translation at once, for one rotation (seed 000 Fig. 1c and
// Fig. 5 bottom row): the pointwise product of the spectra plus one inverse FFT.
#include <Eigen/Core>
#include <vector>

#include "core/grid.h"
#include "engine/program_cache.h"
#include "engine/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

struct TranslationMap {
  GridSpec grid;              // translations t of part 2 (part 1's frame), regular order
  std::vector<float> energy;  // E(R, t) = -Re f; NaN where the periodic sum would alias
  double seconds = 0;
};

// `modes` = 0 keeps every mode; otherwise the low-pass ball holding about that many.
TranslationMap translational_energy_map(const FftLibrary& library, const ComputeContext& ctx,
                                        const PairSpectra& spectra, const Eigen::Matrix3d& rotation,
                                        Interpolation interpolation, std::size_t modes = 0,
                                        const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
