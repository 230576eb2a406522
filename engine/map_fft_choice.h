#pragma once
// Which inverse FFT makes full maps fastest on this device at this size: every backend
// this build has (engine/map_fft.h) maps the same few rotations through a
// TranslationMapper as a search does (scan_rotations: two in flight, each map's minima
// found, on the device with clFFT); the fewest seconds per map wins.
// The pick and its timings are cached per (device, driver, FFT size, interpolation, the
// map kernels' source, backends built) under cache_root()/map_fft (io/cache_file.h), so
// a size is measured once per device.
#include <string>
#include <vector>

#include "engine/full_map.h"
#include "engine/map_fft.h"

namespace snapfit {

struct MapFftTiming {
  MapFft fft = MapFft::clfft;
  double seconds = 0;  // seconds per map with its minima, two in flight
};

struct MapFftChoice {
  MapFft fft = MapFft::clfft;
  std::vector<MapFftTiming> timings;  // every backend built, in map_ffts_built() order
  bool cached = false;                // read from the cache, not measured now
};

// Throws snapfit::Error as TranslationMapper does when a backend fails on the device.
MapFftChoice choose_map_fft(const FftLibrary& library, const ComputeContext& ctx, const PairSpectra& spectra,
                            Interpolation interpolation, std::size_t modes = 0,
                            const ProgramCacheConfig& cache = default_program_cache());

// "fftw (per map: clfft 52.1 ms, fftw 10.3 ms; measured)".
std::string describe_map_fft_choice(const MapFftChoice& choice);

}  // namespace snapfit
