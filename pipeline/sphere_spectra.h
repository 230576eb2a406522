#pragma once
// Pair spectra where one or both parts take seed 001's route (a scene part's
// "descriptor": {"source": "spheres"}): the part's spherical decomposition
// (engine/fields/sphere_decomposition.h) and the analytic transforms of its balls summed onto the
// pair's lattice (engine/spectra/ball_spectrum.h), in place of the FFT of its sampled indicator.
//
// The part's density is c * sum_j 1_{B_j}, whose support is the union of the balls
// (seed 001 eq. 6); c = |S| / sum_j |B_j| makes its integral, the zero mode, the solid's
// volume as for the sampled indicator. Part 2's deconvolved spectrum (the exact rotation,
// engine/spectra/es_kernel.h) is made from the same density sampled on its grid.
#include <functional>
#include <string>
#include <vector>

#include "engine/spectra/ball_spectrum.h"
#include "engine/spectra/spectra.h"
#include "pipeline/assembly_pair.h"

namespace snapfit {

// What a part's source adds to the spectra cache key: "grid", or "spheres" with every
// parameter that changes the balls or their spectrum.
std::string spectrum_source_key(const PartDescriptorSpec& spec, double spacing);

// The number of balls containing each point of `grid`, times `weight` (grid order).
std::vector<float> ball_density_on_grid(const std::vector<Ball>& balls, double weight, const GridSpec& grid);

// The ball count from which the type-1 NUFFT is faster than the direct NDFT onto `modes`
// lattice nodes, as measured on PoCL's CPU device (perf/bench_ndft_crossover).
std::size_t nufft_from_balls(std::size_t modes);

// "direct" or "nufft" for `balls` balls onto `modes` modes, as `method` ("auto": direct
// below nufft_from_balls(modes)).
std::string ball_spectrum_method(const std::string& method, std::size_t balls, std::size_t modes);

// Stage 3 with at least one "spheres" part. `note` gets one line per such part (balls, method, time).
PairSpectra compute_sphere_pair_spectra(const AssemblyPair& pair, const ComputeContext& ctx, const FftLibrary& fft,
                                        const SpectrumOptions& options, const DescriptorOptions& descriptors,
                                        const std::function<void(const std::string&)>& note);

}  // namespace snapfit
