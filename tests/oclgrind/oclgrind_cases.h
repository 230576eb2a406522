#pragma once
// Every kernel variant the engine builds, as small cases that run in seconds on Oclgrind
// (docs/portability.md): the same cases run there with its checks on and on PoCL, and
// the results are compared (tests/oclgrind/test_oclgrind_*.cpp).
#include <string>
#include <utility>
#include <vector>

#include "engine/fields/descriptors.h"
#include "engine/spectra/spectra.h"
#include "mesh/mesh.h"
#include "snapfit/pose.h"
#include "snapfit/query.h"

namespace snapfit::test {

// Part 1, a hole block, and part 2, a peg, both 8-gons: 64 and 32 triangles.
struct SmallPair {
  Mesh part1, part2;
  DescriptorParams params;  // skeletal density, sigma 0.5, tolerance 0.1
  GridSpec grid1, grid2;    // spacing 0.6: the fields the spectra are made of
  GridSpec coarse1;         // part 1 at spacing 0.8 (6 x 6 x 5 points): the descriptor cases
  GridSpec coarse2;         // part 2 at spacing 0.8 (5 x 5 x 6 points): the brute-force case
};
const SmallPair& small_pair();

// A launch of the descriptor passes, and the kernels it runs.
struct DescriptorCase {
  std::string name;
  DescriptorParams params;
  DescriptorOptions options;
  bool part2 = false;      // part 2 on coarse2 (else part 1 on coarse1)
  bool at_points = false;  // descriptors_at_points (-D EXPLICIT_POINTS) instead of the grid
  std::vector<std::string> kernels;
};
std::vector<DescriptorCase> descriptor_cases();
DescriptorFields run_descriptor_case(const ComputeContext& ctx, const DescriptorCase& c);

// The pair's fields on grid1 and grid2, computed once per process on PoCL.
const std::pair<DescriptorFields, DescriptorFields>& pocl_pair_fields();

// Their spectra (FFT grid 14 x 14 x 18), computed once per process on PoCL: every query
// case gets the same input on both devices. The FftLibrary it needs lives only while
// they are computed: clFFT's teardown releases what it built for every context, so a
// library must go before the Oclgrind contexts it served.
const PairSpectra& pocl_pair_spectra();

// Part 2 near and in the hole, turned a little (not at all for translation only): every
// energy, force and torque the variant computes is non-zero.
std::vector<Pose> contact_poses(bool translation_only);

struct QueryCase {
  std::string name;
  QueryVariant variant;
  std::size_t modes;  // m'
  std::vector<std::string> kernels;
};
std::vector<QueryCase> query_cases();

// Launch shapes beside each device's own (the engine's environment overrides,
// engine/query/query_launch.h), set while a query engine is made.
struct LaunchShape {
  std::string name;
  std::vector<std::pair<std::string, std::string>> env;
};
std::vector<LaunchShape> query_launch_shapes();

// results[i] for poses[i] from a batch, then pose 1 again as a single query (the kernel
// argument path instead of the pose buffer).
std::vector<QueryResult> run_query_case(const ComputeContext& ctx, const PairSpectra& spectra, const QueryCase& c,
                                        const LaunchShape& shape);

}  // namespace snapfit::test
