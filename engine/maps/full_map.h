#pragma once
// The score for every translation at once, for one rotation (seed 000 Fig. 1c and
// Fig. 5 bottom row): the pointwise product of the spectra plus one inverse FFT.
#include <CL/opencl.hpp>
#include <Eigen/Core>
#include <array>
#include <memory>
#include <vector>

#include "core/grid.h"
#include "engine/maps/device_minima.h"
#include "engine/maps/map_fft.h"
#include "engine/maps/map_minima.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "snapfit/maps.h"
#include "snapfit/query.h"

namespace snapfit {

// Seconds of each stage of one map, run one after the other (TranslationMapper::time_stages
// and time_minima_stages).
struct MapStageSeconds {
  double product = 0;  // the product kernel, on the device
  double fft = 0;      // the inverse FFT (device or host)
  double reduce = 0;   // the minima kernel, on the device (clFFT's minima)
  double read = 0;     // device to host copy: the map, or the list of minima
  double host = 0;     // the map into E(R, t) in grid order, with the aliasing mask
  double minima = 0;   // on the host: map_minima and the lowest E on the map, or the list's thinning
};

// What a slot's map is submitted for: the map itself (collect), or its minima only
// (collect_minima).
enum class MapOutput { energy, minima };

// How a mapper's minima were found, over its life.
struct MapMinimaCounts {
  std::size_t on_device = 0;   // maps reduced on the device (engine/maps/device_minima.h)
  std::size_t on_host = 0;     // maps whose minima were found in the whole map on the host
  std::size_t fallbacks = 0;   // of those, maps meant for the device: its list overflowed, or E was infinite
  std::size_t longest = 0;     // the longest list of minima a device map had (E <= 0)
  std::size_t long_lists = 0;  // device maps whose list was longer than its first read
};

class StageLap;  // engine/maps/full_map.cpp: the timed stages' stopwatch

// Maps of one pair for many rotations on one device: both spectra uploaded, the product
// kernel built and the inverse FFT planned once. Two slots pipeline the work: while the
// host finishes one slot's maps, the device computes the other's (one in-order queue).
// A slot holds a batch of up to batch() rotations: one product launch for all of them,
// one batched inverse FFT, their minima reduced into a list each, so a GPU gets a few
// large launches per batch instead of a few small ones per rotation.
// With MapFft::clfft the queue runs the product, clFFT's inverse into the slot's map and
// a non-blocking read of the complex map, or, for MapOutput::minima, the minima kernel
// (engine/maps/device_minima.h) and a read of its short list; MapFft::vkfft is the same with
// VkFFT's inverse (engine/spectra/vkfft_inverse.h); with MapFft::fftw it runs the
// product on the half spectrum and a non-blocking read of that, and collect() (or
// collect_minima(), which then finds the minima on the host) runs FFTW's complex-to-real
// inverse on the host.
class TranslationMapper {
 public:
  // `modes` = 0 keeps every mode; otherwise the low-pass ball holding about that many.
  // `batch`: rotations per slot (1 for MapFft::fftw, whose inverse runs on the host one
  // map at a time). Throws snapfit::Error naming the device when a buffer, kernel or
  // plan fails, and for a batch of 0, a batch on FFTW, or one too large for the device
  // (map_batch_limit).
  TranslationMapper(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                    Interpolation interpolation, std::size_t modes = 0, MapFft fft = MapFft::clfft,
                    const ProgramCacheConfig& cache = default_program_cache(), std::size_t batch = 1);
  ~TranslationMapper();
  TranslationMapper(const TranslationMapper&) = delete;
  TranslationMapper& operator=(const TranslationMapper&) = delete;

  static constexpr int slots = 2;
  const GridSpec& grid() const { return grid_; }  // the translations of every map
  MapFft fft() const { return fft_kind_; }
  std::size_t batch() const { return batch_; }
  // Enqueues the maps of part 2 turned by R[0..count) (1 <= count <= batch()) into `slot`
  // (0 or 1) and returns at once; maps the slot held and nobody collected are dropped.
  void submit(int slot, const Eigen::Matrix3d* R, std::size_t count, MapOutput output = MapOutput::energy);
  void submit(int slot, const Eigen::Matrix3d& R, MapOutput output = MapOutput::energy) { submit(slot, &R, 1, output); }
  // Waits for the slot's maps and writes the member-th one's E(R, t) in grid order into
  // `energy` (NaN where the periodic sum would alias). Throws snapfit::Error for a member
  // not submitted or already collected, or a slot submitted for its minima.
  void collect(int slot, std::vector<float>& energy, std::size_t member = 0);
  // Waits for the slot's maps and writes what map_minima(grid(), E, count, separation)
  // gives on the member-th one's energy, and that map's lowest finite E. A slot submitted
  // for its minima on a device FFT reads only the device's list of minima (the whole map
  // when that list overflowed or E was infinite); any other slot finds them in the whole
  // map on the host. Throws snapfit::Error for a member not submitted or already collected.
  void collect_minima(int slot, std::size_t count, double separation, MapMinimaResult& out, std::size_t member = 0);
  // submit + collect.
  TranslationMap map(const Eigen::Matrix3d& R);
  // One map with every stage waited for and timed in turn (no overlap), for benchmarks.
  MapStageSeconds time_stages(const Eigen::Matrix3d& R, std::vector<float>& energy);
  // The same for submit(.., MapOutput::minima) + collect_minima.
  MapStageSeconds time_minima_stages(const Eigen::Matrix3d& R, std::size_t count, double separation,
                                     MapMinimaResult& out);
  // True when MapOutput::minima reduces the maps on the device (clFFT, VkFFT).
  bool minima_on_device() const { return map_fft_on_device(fft_kind_); }
  MapMinimaCounts minima_counts() const;

 private:
  struct Slot;
  struct HostFft;
  struct VkFft;
  void enqueue_product(int slot);
  void enqueue_fft(int slot);
  void enqueue_read(int slot, cl::Event* done);
  void wait_for(int slot, std::size_t member);
  void aliasing_mask(const Eigen::Matrix3d& R, std::array<std::vector<char>, 3>& inside) const;
  MapBox aliasing_box(const Eigen::Matrix3d& R);
  void finish_map(int slot, std::size_t member, std::vector<float>& energy, MapStageSeconds* stages);
  void host_minima(int slot, std::size_t member, std::size_t count, double separation, MapMinimaResult& out,
                   MapStageSeconds* stages);
  int minima_list(int slot, std::size_t member) const { return slot * int(batch_) + int(member); }
  // For the timed stages: waits for both slots, then the product and (on the device) the
  // inverse FFT into slot 0, each waited for and timed by `lap`.
  void time_product_and_fft(const Eigen::Matrix3d& R, MapStageSeconds& t, StageLap& lap);
  const ComputeContext& ctx_;
  const PairSpectra& spectra_;
  GridSpec grid_;
  float max_w2_;
  std::size_t batch_;
  cl::Kernel kernel_;
  cl::Buffer s1_, s2_, product_;
  MapFft fft_kind_;
  std::unique_ptr<Fft3d> fft_;                   // clfft
  std::unique_ptr<DeviceMinima> device_minima_;  // clfft, vkfft
  cl::CommandQueue side_;                    // clfft, vkfft: reads of a collected slot while the queue runs the other
  std::unique_ptr<HostFft> host_fft_;        // fftw
  std::unique_ptr<VkFft> vkfft_;             // vkfft
  std::vector<std::size_t> fft_index_;       // grid index -> FFT index of the same translation
  std::vector<float> energy_;                // collect_minima's map on the host
  std::array<std::vector<char>, 3> inside_;  // per axis: the translations that do not alias
  MapMinimaCounts counts_;
  std::unique_ptr<Slot[]> slot_;
};

// The largest batch up to `wanted` whose maps fit the device: each of a mapper's three
// buffers of batch x dims complex floats (the products and the two slots' maps) within
// the device's largest allocation, all three within a quarter of its global memory.
// At least 1.
std::size_t map_batch_limit(const ComputeContext& ctx, const std::array<std::size_t, 3>& dims, std::size_t wanted);

// One map (a TranslationMapper used once).
TranslationMap translational_energy_map(const FftLibrary& library, const ComputeContext& ctx,
                                        const PairSpectra& spectra, const Eigen::Matrix3d& rotation,
                                        Interpolation interpolation, std::size_t modes = 0,
                                        const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
