#pragma once
// On-disk cache of pair spectra (engine/spectra/spectra.h), in the versioned, checksummed,
// atomically written container of io/cache_file.h, under cache_root()/spectra. The key
// hashes both affinity fields and their grids, the oversampling, the exact-rotation kernel
// and where each part's spectrum comes from (pipeline/sphere_spectra.h spectrum_source_key).
#include <functional>
#include <optional>
#include <string>

#include "engine/spectra/spectra.h"

namespace snapfit {

std::string spectra_cache_key(const DescriptorFields& part1, const DescriptorFields& part2,
                              const SpectrumOptions& options, const std::string& source1, const std::string& source2);

// Nothing when missing; a stale or corrupt entry is reported through `note` and ignored.
std::optional<PairSpectra> load_cached_spectra(const std::string& key,
                                               const std::function<void(const std::string&)>& note);

// A write failure is reported through `note`, never thrown.
void save_cached_spectra(const std::string& key, const PairSpectra& spectra,
                         const std::function<void(const std::string&)>& note);

}  // namespace snapfit
