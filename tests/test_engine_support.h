#pragma once
// Shared by the tests that run kernels: one OpenCL context on the default device, and
// one program-cache folder for the whole run (kernels compile once), quiet.
#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/runtime/program_cache.h"
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

}  // namespace snapfit::test
