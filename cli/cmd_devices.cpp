// `snapfit devices`: every OpenCL device with the capabilities that matter here;
// `--check` builds and runs the self-check kernel on each.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "engine/runtime/device.h"
#include "engine/runtime/device_check.h"
#include "report/device_json.h"
#include "snapfit/error.h"

namespace snapfit::cli {
namespace {

struct DevicesOptions {
  bool check = false;
  bool json = false;
};

const char* origin_name(ProgramOrigin o) {
  switch (o) {
    case ProgramOrigin::compiled:
      return "compiled";
    case ProgramOrigin::cache_hit:
      return "cache hit";
    case ProgramOrigin::recompiled_after_bad_cache:
      return "recompiled (bad cache entry)";
  }
  return "?";
}

nlohmann::json check_json(const DeviceCheckResult& r) {
  return {{"precision", r.precision},
          {"passed", r.passed},
          {"relative_error", r.relative_error},
          {"tolerance", r.tolerance},
          {"program", origin_name(r.origin)},
          {"build_ms", r.build_ms},
          {"kernel_ms", r.kernel_ms}};
}

void run_devices(const DevicesOptions& opt) {
  const std::vector<Device> devices = enumerate_devices();
  if (devices.empty()) throw Error("no OpenCL device found: install an OpenCL driver (Debian: pocl-opencl-icd)");
  std::vector<DeviceInfo> infos;
  for (const Device& d : devices) infos.push_back(d.info);
  const std::size_t chosen = select_device_index(infos, device_spec_from(""));
  bool all_passed = true;
  for (const Device& d : devices) {
    const DeviceInfo& i = d.info;
    nlohmann::json checks = nlohmann::json::array();
    if (opt.check) {
      const ComputeContext ctx = make_compute_context(d);
      for (bool dbl : {false, true}) {
        if (dbl && !i.fp64) continue;
        const DeviceCheckResult r = run_device_check(ctx, dbl);
        all_passed = all_passed && r.passed;
        checks.push_back(check_json(r));
      }
    }
    if (opt.json) {
      nlohmann::json j = device_json(i);
      j["selected"] = static_cast<std::size_t>(i.index) == chosen;
      if (opt.check) j["check"] = checks;
      std::cout << j.dump() << "\n";
      continue;
    }
    std::cout << (static_cast<std::size_t>(i.index) == chosen ? "* " : "  ") << describe_device(i) << "\n"
              << "      compute units " << i.compute_units << ", global memory " << std::fixed << std::setprecision(1)
              << i.global_memory_bytes / 1073741824.0 << " GiB (max alloc " << i.max_alloc_bytes / 1073741824.0
              << " GiB), local memory " << i.local_memory_bytes / 1024 << " KiB, max work-group "
              << i.max_work_group_size << ", fp64 " << (i.fp64 ? "yes" : "no") << "\n"
              << "      " << i.device_version << "\n";
    for (const auto& c : checks) {
      std::cout << "      check " << c["precision"].get<std::string>() << ": "
                << (c["passed"].get<bool>() ? "passed" : "FAILED") << std::scientific << std::setprecision(2)
                << " (relative error " << c["relative_error"].get<double>() << ", tolerance "
                << c["tolerance"].get<double>() << std::fixed << std::setprecision(1) << "; program "
                << c["program"].get<std::string>() << " in " << c["build_ms"].get<double>() << " ms)\n";
    }
  }
  if (!opt.json) std::cout << "* = the device used by default (override with --device or SNAPFIT_DEVICE)\n";
  if (!all_passed) throw Error("a device failed its self-check (see above)");
}

}  // namespace

void add_devices_command(CLI::App& app) {
  auto opt = std::make_shared<DevicesOptions>();
  CLI::App* cmd = app.add_subcommand("devices", "List every OpenCL platform and device, with capabilities");
  cmd->add_flag("--check", opt->check,
                "Build and run the self-check kernel on every device (float, and double where supported)");
  cmd->add_flag("--json", opt->json, "One JSON object per device");
  cmd->callback([opt] { run_devices(*opt); });
}

}  // namespace snapfit::cli
