#pragma once
// What the processes of one search send each other (snapfit/search.h SearchExchange),
// as doubles: part 1's and part 2's spectra, and the maps' candidates.
#include <vector>

#include "engine/maps/rotation_search.h"
#include "engine/spectra/spectra.h"

namespace snapfit {

// Header, then both parts' centres, extents, parities and spectra (not the deconvolved
// spectrum, which the maps do not use).
std::vector<double> encode_spectra(const PairSpectra& spectra);
// Throws snapfit::Error when the values are not a whole encoding.
PairSpectra decode_spectra(const std::vector<double>& values);

// Each candidate as (rotation, cell, energy, t); its rotation is looked up in `rotations`
// when decoded. Throws snapfit::Error for a rotation index outside `rotations`.
std::vector<double> encode_candidates(const std::vector<PoseCandidate>& candidates);
std::vector<PoseCandidate> decode_candidates(const std::vector<double>& values,
                                             const std::vector<Eigen::Quaterniond>& rotations);

}  // namespace snapfit
