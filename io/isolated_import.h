#pragma once
// Runs a piece of work in a forked child process under an address-space and a CPU-time
// limit and returns the bytes it produced, so that a library that runs away (allocates
// gigabytes, crashes, loops) on a malformed file cannot take the caller with it (as
// Assimp does on some fuzzed .x and .dae files). io/import_child.h runs the importers
// (Assimp, OpenCASCADE) this way.
//
// The child is a fork of a process that may have other threads (TBB, OpenCL): the work
// must not start threads or rely on locks another thread may hold. glibc's malloc is
// safe to use after fork. The child's stdout is /dev/null (its reply goes through a pipe).
#include <cstdint>
#include <functional>
#include <string>

namespace snapfit {

struct ChildLimits {
  // Address space the child may add to what it inherits from the parent (RLIMIT_AS is
  // set to the parent's current size plus this; free space in the parent's heap is
  // inherited too, so the child may use that on top).
  std::uint64_t memory_mib = 1024;
  // CPU seconds (RLIMIT_CPU).
  unsigned seconds = 60;
  // Wall-clock seconds after which the parent kills the child: for a child that waits
  // without using the CPU.
  double wall_seconds = 180;
};

struct ChildResult {
  enum class Status {
    ok,             // the work returned; `bytes` is what it returned
    error,          // it threw snapfit::Error; `bytes` is the message, unchanged
    exception,      // it threw another exception; `bytes` is its what()
    out_of_memory,  // std::bad_alloc in the child, or the child was killed (SIGKILL)
    crashed,        // killed by another signal (`signal`)
    timed_out,      // past `seconds` of CPU time or `wall_seconds` of wall time
    bad_reply,      // exited without a complete reply; `bytes` says how
  };
  Status status = Status::bad_reply;
  std::string bytes;
  int signal = 0;
};

// Forks, runs `work` in the child under `limits` and waits for it. Only a failure to
// start the child (no pipe, no fork) throws snapfit::Error; every way the child can fail
// is a ChildResult. The child is always reaped, also when this function throws.
ChildResult run_in_child(const std::function<std::string()>& work, const ChildLimits& limits);

}  // namespace snapfit
