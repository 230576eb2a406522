#pragma once
// The score for every translation at once, for one rotation (seed 000 Fig. 1c and
// Fig. 5 bottom row): the pointwise product of the spectra plus one inverse FFT.
#include <CL/opencl.hpp>
#include <Eigen/Core>
#include <array>
#include <memory>
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

// Maps of one pair for many rotations on one device: both spectra uploaded, the product
// kernel built and the inverse FFT plan baked once. Two slots pipeline the work: while
// the host reads one slot's map, the device computes the other's (one in-order queue:
// product, inverse FFT, then a non-blocking read into that slot's host buffer).
class TranslationMapper {
 public:
  // `modes` = 0 keeps every mode; otherwise the low-pass ball holding about that many.
  // Throws snapfit::Error naming the device when a buffer, kernel or plan fails.
  TranslationMapper(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                    Interpolation interpolation, std::size_t modes = 0,
                    const ProgramCacheConfig& cache = default_program_cache());
  ~TranslationMapper();
  TranslationMapper(const TranslationMapper&) = delete;
  TranslationMapper& operator=(const TranslationMapper&) = delete;

  static constexpr int slots = 2;
  const GridSpec& grid() const { return grid_; }  // the translations of every map
  // Enqueues the map of part 2 turned by R into `slot` (0 or 1) and returns at once.
  void submit(int slot, const Eigen::Matrix3d& R);
  // Waits for the slot's map and writes E(R, t) in grid order into `energy` (NaN where
  // the periodic sum would alias). Throws snapfit::Error for a slot with nothing submitted.
  void collect(int slot, std::vector<float>& energy);
  // submit + collect.
  TranslationMap map(const Eigen::Matrix3d& R);

 private:
  struct Slot;
  const ComputeContext& ctx_;
  const PairSpectra& spectra_;
  GridSpec grid_;
  float max_w2_;
  cl::Kernel kernel_;
  cl::Buffer s1_, s2_, product_, result_;
  std::unique_ptr<Fft3d> fft_;
  std::vector<std::size_t> fft_index_;  // grid index -> FFT index of the same translation
  std::unique_ptr<Slot[]> slot_;
};

// One map (a TranslationMapper used once).
TranslationMap translational_energy_map(const FftLibrary& library, const ComputeContext& ctx,
                                        const PairSpectra& spectra, const Eigen::Matrix3d& rotation,
                                        Interpolation interpolation, std::size_t modes = 0,
                                        const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
