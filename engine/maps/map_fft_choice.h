#pragma once
// Which inverse FFT, and how many rotations per batch, make full maps fastest on this
// device at this size: every backend this build has (engine/maps/map_fft.h), one rotation at
// a time and, for the device FFTs, also in batches (kMapBatch, or what fits the device),
// maps the same rotations through a TranslationMapper as a search does (scan_rotations:
// two batches in flight, each map's minima found, on the device with a device FFT); the
// fewest seconds per map wins.
// The pick and its timings are cached per (device, driver, FFT size, interpolation, the
// map kernels' source, backends built) under cache_root()/map_fft (io/cache_file.h), so
// a size is measured once per device.
#include <string>
#include <vector>

#include "engine/maps/full_map.h"
#include "engine/maps/map_fft.h"

namespace snapfit {

// The batch tried beside one rotation at a time on the device FFTs.
constexpr std::size_t kMapBatch = 8;

struct MapFftTiming {
  MapFft fft = MapFft::clfft;
  std::size_t batch = 1;  // rotations per batch
  double seconds = 0;     // seconds per map with its minima, two batches in flight
};

struct MapFftChoice {
  MapFft fft = MapFft::clfft;
  std::size_t batch = 1;
  // Every backend built, in map_ffts_built() order, each with batch 1, then the device
  // FFTs' batched runs when a batch larger than 1 fits (map_batch_limit).
  std::vector<MapFftTiming> timings;
  bool cached = false;  // read from the cache, not measured now
};

// Throws snapfit::Error as TranslationMapper does when a backend fails on the device.
MapFftChoice choose_map_fft(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                            Interpolation interpolation, std::size_t modes = 0,
                            const ProgramCacheConfig& cache = default_program_cache());

// "clfft x8 (per map: clfft 52.1 ms, fftw 10.3 ms, clfft x8 9.7 ms; measured)".
std::string describe_map_fft_choice(const MapFftChoice& choice);

}  // namespace snapfit
