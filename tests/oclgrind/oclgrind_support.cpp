#include "tests/oclgrind/oclgrind_support.h"

#include <doctest/doctest.h>
#include <fstream>
#include <iterator>

#include "snapfit/error.h"

namespace snapfit::test {

Device oclgrind_device() {
  for (const Device& d : enumerate_devices())
    if (d.info.is_simulator() && d.info.platform_name == "Oclgrind") return d;
  throw Error(
      "Oclgrind is not an OpenCL platform here: install the Debian package oclgrind (`bash .ci/setup`) and run with "
      "OCL_ICD_VENDORS=build/oclgrind-vendors, as CTest does (docs/portability.md)");
}

OclgrindSession::OclgrindSession(const OclgrindChecks& checks) : checks_(checks), log_path_(dir_.file("oclgrind.log")) {
  const Device device = oclgrind_device();
  // Oclgrind's plugins read these when the context is made and keep them (OCLGRIND_CHECK_API
  // only adds stderr copies of the API errors the context's callback receives anyway).
  EnvScope log("OCLGRIND_LOG", log_path_.c_str());
  EnvScope races("OCLGRIND_DATA_RACES", "1");
  EnvScope uninitialized("OCLGRIND_UNINITIALIZED", checks.uninitialized ? "1" : nullptr);
  EnvScope api("OCLGRIND_CHECK_API", "1");
  // Oclgrind counts reports per process and drops those past the limit (1000 by default):
  // a later session would look clean.
  EnvScope limit("OCLGRIND_MAX_ERRORS", "100000000");
  auto notify = [](const char* message, const void*, std::size_t, void* user) {
    auto* errors = static_cast<ApiErrors*>(user);
    std::lock_guard<std::mutex> lock(errors->mutex);
    errors->text += std::string(message) + "\n";
  };
  ctx_.device = device;
  ctx_.context = cl::Context(device.device, nullptr, notify, api_errors_.get());
  ctx_.queue = cl::CommandQueue(ctx_.context, device.device, CL_QUEUE_PROFILING_ENABLE);
}

const std::vector<UninitializedDefect>& uninitialized_check_defects() {
  // Found in the LLVM IR Oclgrind builds (OCLGRIND_DUMP_SPIR=1) for the engine's stages.
  static const std::vector<UninitializedDefect> defects = [] {
    const std::string shuffle =
        "a shufflevector with undef mask lanes: the plugin crashes with SIGSEGV "
        "(tests/data/oclgrind/undef_shuffle_lanes.cl)";
    const std::string freeze =
        "freeze (a quotient and remainder of the same operands): the plugin stops the kernel with 'Unsupported "
        "instruction: freeze' (tests/data/oclgrind/freeze.cl)";
    return std::vector<UninitializedDefect>{
        {"winding_number", shuffle},  // in first_order_term
        {"rotated_product", shuffle},
        {"skeletal_density", freeze + "; in some variants also " + shuffle},
        {"pose_query", freeze + "; and " + shuffle},
        {"translation_lines", freeze + "; and " + shuffle},
        {"rotated_lines", freeze + "; and " + shuffle},
        {"spectrum_product", freeze},
        {"fft_fwd", freeze + " (clFFT's generated kernel)"},
        {"fft_back", freeze + " (clFFT's generated kernel)"},
    };
  }();
  return defects;
}

OclgrindChecks checks_for(const std::vector<std::string>& kernels) {
  OclgrindChecks checks;
  for (const std::string& k : kernels)
    for (const UninitializedDefect& d : uninitialized_check_defects())
      if (d.kernel == k) checks.uninitialized = false;
  return checks;
}

const std::vector<ThirdPartyReport>& known_third_party_reports() {
  static const std::vector<ThirdPartyReport> known = [] {
    const std::string why =
        "clFFT's generated in-place passes read and write the same global elements from different work-items of a "
        "group with only a local-memory barrier between (docs/portability.md \"clFFT\")";
    return std::vector<ThirdPartyReport>{{"fft_fwd", "data race", why}, {"fft_back", "data race", why}};
  }();
  return known;
}

namespace {

// Oclgrind's log, split into reports: each starts with an unindented line (the kind of
// report) and goes on with indented lines, one of them "Kernel: <name>".
std::vector<std::string> split_reports(const std::string& log) {
  std::vector<std::string> reports;
  std::size_t start = 0;
  while (start < log.size()) {
    std::size_t end = log.find('\n', start);
    if (end == std::string::npos) end = log.size();
    const std::string line = log.substr(start, end - start);
    if (!line.empty() && line[0] != '\t' && line[0] != ' ')
      reports.push_back(line + "\n");
    else if (!reports.empty() && !line.empty())
      reports.back() += line + "\n";
    start = end + 1;
  }
  return reports;
}

bool is_known(const std::string& report) {
  for (const ThirdPartyReport& k : known_third_party_reports())
    if (report.find(k.kind) < report.find('\n') && report.find("Kernel: " + k.kernel + "\n") != std::string::npos)
      return true;
  return false;
}

}  // namespace

std::string OclgrindSession::take_reports(std::size_t* left_out) {
  ctx_.queue.finish();
  std::ifstream in(log_path_, std::ios::binary);
  const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string fresh = log.size() > log_read_ ? log.substr(log_read_) : std::string();
  log_read_ = log.size();
  std::string reports;
  std::size_t known = 0, kept = 0;
  for (const std::string& r : split_reports(fresh)) {
    if (is_known(r)) {
      ++known;
      continue;
    }
    // The first few in full (a kernel with a fault reports it at every work-item).
    if (++kept <= 8) reports += r + "\n";
  }
  if (kept > 8) reports += "... and " + std::to_string(kept - 8) + " more reports\n";
  if (left_out) *left_out = known;
  std::lock_guard<std::mutex> lock(api_errors_->mutex);
  reports += api_errors_->text;
  api_errors_->text.clear();
  return reports;
}

void expect_clean(OclgrindSession& session, const std::string& what) {
  std::size_t left_out = 0;
  const std::string reports = session.take_reports(&left_out);
  CHECK_MESSAGE(reports.empty(), what << ": Oclgrind reported:\n" << reports);
  if (left_out > 0)
    MESSAGE(what << ": " << left_out << " reports on clFFT's kernels left out (known_third_party_reports)");
}

}  // namespace snapfit::test
