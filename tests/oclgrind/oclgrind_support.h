#pragma once
// Oclgrind, the OpenCL device simulator, for the tests of the `oclgrind` label
// (docs/portability.md): a context on its device with its checks on, and what they report.
//
// Checks (Oclgrind reads them from its environment when a context is made, so each
// session has its own): invalid memory accesses and barrier divergence (always on), data
// races in local and global memory (OCLGRIND_DATA_RACES), uses of uninitialised values
// (OCLGRIND_UNINITIALIZED) and API misuse (OCLGRIND_CHECK_API, and the context callback).
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "tests/test_support.h"

namespace snapfit::test {

// Oclgrind's device from the OpenCL platforms; throws snapfit::Error naming the fix when
// the loader does not list it.
Device oclgrind_device();

struct OclgrindChecks {
  // Off where Oclgrind 21.10's uninitialised-value plugin cannot run a kernel of the
  // launch (uninitialized_check_defects); every other check is always on.
  bool uninitialized = true;
};

// The kernels whose code, as Oclgrind 21.10 compiles it, holds an instruction its
// uninitialised-value plugin cannot run (docs/portability.md "Oclgrind's uninitialised-
// value check"): kernel name and defect, with its reproducer in tests/data/oclgrind.
struct UninitializedDefect {
  std::string kernel;
  std::string defect;
};
const std::vector<UninitializedDefect>& uninitialized_check_defects();

// The checks for a launch that runs `kernels`: the uninitialised-value check only when
// none of them is in uninitialized_check_defects.
OclgrindChecks checks_for(const std::vector<std::string>& kernels);

// Reports on code that is not snapfit's and that it cannot change: a kind of report
// (the text that starts it, e.g. "data race") in a kernel, and why it is left out.
struct ThirdPartyReport {
  std::string kernel;
  std::string kind;
  std::string reason;
};
const std::vector<ThirdPartyReport>& known_third_party_reports();

class OclgrindSession {
 public:
  explicit OclgrindSession(const OclgrindChecks& checks = {});
  OclgrindSession(const OclgrindSession&) = delete;
  OclgrindSession& operator=(const OclgrindSession&) = delete;

  const ComputeContext& context() const { return ctx_; }
  const OclgrindChecks& checks() const { return checks_; }
  // What Oclgrind reported since the last call, each report naming the kernel, the
  // work-item and the instruction, with API errors; "" when clean. Reports of
  // known_third_party_reports are left out and counted in `left_out`.
  std::string take_reports(std::size_t* left_out = nullptr);

 private:
  struct ApiErrors {
    std::mutex mutex;
    std::string text;
  };
  OclgrindChecks checks_;
  TempDir dir_;
  std::string log_path_;
  std::size_t log_read_ = 0;
  std::shared_ptr<ApiErrors> api_errors_ = std::make_shared<ApiErrors>();
  ComputeContext ctx_;
};

// A doctest check that Oclgrind reported nothing on snapfit's kernels since the last take
// (`what` names the step); reports left out as third-party are counted in a message.
void expect_clean(OclgrindSession& session, const std::string& what);

}  // namespace snapfit::test
