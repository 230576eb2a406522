#pragma once
// The local minima of full translational maps found on the OpenCL device
// (kernels/map_minima.cl), so a search reads back a short list per rotation instead of
// the whole map: the same minima in the same order, with the same energies, as
// map_minima (engine/maps/map_minima.h) on the map in grid order, and the same lowest energy.
//
// A map is the complex inverse FFT in FFT order, E = -Re f (engine/maps/full_map.h, the clFFT
// and VkFFT paths). Each of a few lists lives on the device, so the maps of a pipeline
// (every map of TranslationMapper's batches in flight) never share one: enqueue a list's
// reduction and read on the in-order queue after the map's FFT, wait for the read, then
// finish(). The lists are called slots below.
#include <CL/opencl.hpp>
#include <array>
#include <cstddef>
#include <vector>

#include "core/grid.h"
#include "engine/runtime/compute_context.h"
#include "engine/maps/map_minima.h"
#include "engine/runtime/program_cache.h"

namespace snapfit {

// The grid indices, per axis and inclusive, whose translations do not alias: a map's
// aliasing mask is a box (engine/maps/full_map.cpp), E = NaN outside it. Empty when lo > hi.
struct MapBox {
  std::array<int, 3> lo{{0, 0, 0}}, hi{{-1, -1, -1}};
};

class DeviceMinima {
 public:
  // Maps of `dims` points in `slots` slots. Each slot's list holds `capacity` minima; 0
  // (the default) takes the most a map of dims can have, ceil(N_x/2) ceil(N_y/2) ceil(N_z/2)
  // (no two neighbours are both minima, so each 2 x 2 x 2 block holds at most one): the
  // list cannot overflow. One work-item per point, groups of 64 along x. SNAPFIT_MINIMA_WG and
  // SNAPFIT_MINIMA_CAPACITY override the group size and the capacity (for measurements on
  // other devices and the tests of the overflow path). Throws snapfit::Error naming the
  // device when a buffer or the kernel cannot be made.
  DeviceMinima(const ComputeContext& ctx, const std::array<std::size_t, 3>& dims, int slots,
               const ProgramCacheConfig& cache = default_program_cache());
  DeviceMinima(const DeviceMinima&) = delete;
  DeviceMinima& operator=(const DeviceMinima&) = delete;

  // Enqueues on `queue` the reduction of the map in `f` (dims complex floats, FFT order,
  // from element `offset`: a map of a batch) into the slot's list: its counters reset,
  // then the kernel.
  void enqueue_reduce(const cl::CommandQueue& queue, int slot, const cl::Buffer& f, const MapBox& box,
                      std::size_t offset = 0);
  // Enqueues on `queue` a non-blocking read of the slot's counters and of the first
  // entries of its list (as many as the longest list so far, at least 1,024), `done`
  // completing with it.
  void enqueue_read(const cl::CommandQueue& queue, int slot, cl::Event* done);

  // After the slot's read completed: its minima as map_minima(grid, E, count, separation)
  // gives them into `minima`, and the map's lowest finite E into `best` (NaN: none).
  // Entries past the read are read on `side`, a queue with nothing of the slot's pending.
  // Returns false, leaving `minima` and `best` as they were, when the map cannot be
  // reduced on the device: more minima than the list holds, or an infinite E (then the
  // lowest finite E need not be a minimum). The caller reads the whole map instead.
  // Allocates nothing once `minima` and the lists have held as many before.
  bool finish(const cl::CommandQueue& side, int slot, const GridSpec& grid, std::size_t count, double separation,
              std::vector<MapMinimum>& minima, float& best);

  std::size_t capacity() const { return capacity_; }
  std::size_t work_group() const { return wg_; }

  struct Stats {
    std::size_t maps = 0;        // finished
    std::size_t longest = 0;     // the most minima with E <= 0 in one map
    std::size_t long_lists = 0;  // maps whose list was longer than its read: the rest read after
    std::size_t overflows = 0;   // maps with more minima than the list holds
    std::size_t infinities = 0;  // maps with an infinite E
  };
  const Stats& stats() const { return stats_; }

 private:
  const ComputeContext& ctx_;
  std::array<std::size_t, 3> dims_;
  std::size_t capacity_ = 0, wg_ = 64, read_entries_ = 1024;
  cl::Kernel kernel_;
  std::vector<cl::Buffer> lists_;           // per slot: 4 counters, then 2 words per entry
  std::vector<std::vector<cl_uint>> host_;  // per slot, the same on the host
  std::vector<std::size_t> read_;           // per slot: entries its last read brought
  std::vector<MapMinimum> candidates_;      // scratch: the list's minima with E < 0
  Stats stats_;
};

}  // namespace snapfit
