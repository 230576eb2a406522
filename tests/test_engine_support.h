#pragma once
// Shared by the tests that run kernels: one OpenCL context on the default device, and
// one program-cache folder for the whole run (kernels compile once), quiet.
#include <array>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/runtime/program_cache.h"
#include "snapfit/grid.h"
#include "tests/test_support.h"

namespace snapfit::test {

inline const ComputeContext& test_context() {
  static const ComputeContext ctx = make_compute_context(select_device(""));
  return ctx;
}

inline ProgramCacheConfig test_program_cache() {
  static const TempDir dir;
  ProgramCacheConfig config;
  config.directory = dir.file("programs");
  config.note = [](const std::string&) {};
  return config;
}

// A grid of dims points `spacing` apart from `origin`.
inline GridSpec grid_spec(std::array<int, 3> dims, double spacing, const Eigen::Vector3d& origin) {
  GridSpec g;
  g.dims = Eigen::Vector3i(dims[0], dims[1], dims[2]);
  g.spacing = spacing;
  g.origin = origin;
  return g;
}

}  // namespace snapfit::test
