#pragma once
// The score for every translation at once, for one rotation (seed 000 Fig. 1c and
// Fig. 5 bottom row): the pointwise product of the spectra plus one inverse FFT.
#include <CL/opencl.hpp>
#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "core/grid.h"
#include "engine/map_fft.h"
#include "engine/program_cache.h"
#include "engine/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

struct TranslationMap {
  GridSpec grid;              // translations t of part 2 (part 1's frame), regular order
  std::vector<float> energy;  // E(R, t) = -Re f; NaN where the periodic sum would alias
  double seconds = 0;
};

// Seconds of each stage of one map, run one after the other (TranslationMapper::time_stages).
struct MapStageSeconds {
  double product = 0;  // the product kernel, on the device
  double fft = 0;      // the inverse FFT (device or host)
  double read = 0;     // device to host copy
  double host = 0;     // the map into E(R, t) in grid order, with the aliasing mask
};

// Maps of one pair for many rotations on one device: both spectra uploaded, the product
// kernel built and the inverse FFT planned once. Two slots pipeline the work: while the
// host finishes one slot's map, the device computes the other's (one in-order queue).
// With MapFft::clfft the queue runs the product, clFFT's inverse and a non-blocking read
// of the complex map; with MapFft::fftw it runs the product on the half spectrum and a
// non-blocking read of that, and collect() runs FFTW's complex-to-real inverse on the host.
class TranslationMapper {
 public:
  // `modes` = 0 keeps every mode; otherwise the low-pass ball holding about that many.
  // Throws snapfit::Error naming the device when a buffer, kernel or plan fails.
  TranslationMapper(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                    Interpolation interpolation, std::size_t modes = 0, MapFft fft = MapFft::clfft,
                    const ProgramCacheConfig& cache = default_program_cache());
  ~TranslationMapper();
  TranslationMapper(const TranslationMapper&) = delete;
  TranslationMapper& operator=(const TranslationMapper&) = delete;

  static constexpr int slots = 2;
  const GridSpec& grid() const { return grid_; }  // the translations of every map
  MapFft fft() const { return fft_kind_; }
  // Enqueues the map of part 2 turned by R into `slot` (0 or 1) and returns at once.
  void submit(int slot, const Eigen::Matrix3d& R);
  // Waits for the slot's map and writes E(R, t) in grid order into `energy` (NaN where
  // the periodic sum would alias). Throws snapfit::Error for a slot with nothing submitted.
  void collect(int slot, std::vector<float>& energy);
  // submit + collect.
  TranslationMap map(const Eigen::Matrix3d& R);
  // One map with every stage waited for and timed in turn (no overlap), for benchmarks.
  MapStageSeconds time_stages(const Eigen::Matrix3d& R, std::vector<float>& energy);

 private:
  struct Slot;
  struct HostFft;
  void enqueue_product(const Eigen::Matrix3d& R);
  void enqueue_fft();
  void enqueue_read(int slot, cl::Event* done);
  void finish_map(int slot, std::vector<float>& energy, MapStageSeconds* stages);
  const ComputeContext& ctx_;
  const PairSpectra& spectra_;
  GridSpec grid_;
  float max_w2_;
  cl::Kernel kernel_;
  cl::Buffer s1_, s2_, product_, result_;
  MapFft fft_kind_;
  std::unique_ptr<Fft3d> fft_;          // clfft
  std::unique_ptr<HostFft> host_fft_;   // fftw
  std::vector<std::size_t> fft_index_;  // grid index -> FFT index of the same translation
  std::unique_ptr<Slot[]> slot_;
};

// One map (a TranslationMapper used once).
TranslationMap translational_energy_map(const FftLibrary& library, const ComputeContext& ctx,
                                        const PairSpectra& spectra, const Eigen::Matrix3d& rotation,
                                        Interpolation interpolation, std::size_t modes = 0,
                                        const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
