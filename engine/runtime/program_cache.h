#pragma once
// Builds OpenCL programs from embedded sources with -D options, and caches the built
// binaries on disk keyed by device, driver version, source hash and options (so a
// driver update or a kernel edit never reuses a stale binary). A cache entry that is
// stale, corrupt, or refused by the driver is rebuilt from source, with a note.
#include <functional>
#include <string>

#include "engine/runtime/compute_context.h"

namespace snapfit {

struct ProgramCacheConfig {
  std::string directory;                         // "" disables the disk cache; default: cache_root()/programs
  std::function<void(const std::string&)> note;  // messages about cache misuse; default: stderr
};

// The default: cache_root()/programs, notes to stderr.
ProgramCacheConfig default_program_cache();

enum class ProgramOrigin { compiled, cache_hit, recompiled_after_bad_cache };

struct BuiltProgram {
  cl::Program program;
  ProgramOrigin origin = ProgramOrigin::compiled;
  std::string cache_path;  // the entry used or written ("" when caching is off)
  double build_ms = 0.0;   // wall time of this call
  std::string build_log;   // what the compiler said on a build from source ("" if nothing or from the cache)
};

// The exact text the cache key is made of (device, driver, source hash, options).
std::string program_cache_key(const DeviceInfo& device, const std::string& source, const std::string& options);

// Builds `source` (named `name` in messages) for ctx's device with `options`.
// A compile error throws snapfit::Error with the kernel name, device name, options and
// the compiler log. A build from source whose compiler log is not empty (warnings) is a
// note naming the kernel and the device, once. A failure to write the cache is a note, not
// an error.
BuiltProgram build_program(const ComputeContext& ctx, const std::string& name, const std::string& source,
                           const std::string& options, const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
