// `snapfit devices`: every OpenCL device with the capabilities that matter here;
// `--check` builds and runs the self-check kernel on each.
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "report/device_json.h"
#include "snapfit/devices.h"
#include "snapfit/error.h"

namespace snapfit::cli {
namespace {

struct DevicesOptions {
  bool check = false;
  bool json = false;
};

nlohmann::json check_json(const DeviceCheck& c) {
  return {{"precision", c.precision}, {"passed", c.passed},   {"relative_error", c.relative_error},
          {"tolerance", c.tolerance}, {"program", c.program}, {"build_ms", c.build_ms},
          {"kernel_ms", c.kernel_ms}};
}

void run_devices(const DevicesOptions& opt) {
  DeviceListRequest request;
  request.check = opt.check;
  const DeviceList list = list_devices(request);
  bool all_passed = true;
  for (const ListedDevice& d : list.devices) {
    const DeviceInfo& i = d.info;
    nlohmann::json checks = nlohmann::json::array();
    for (const DeviceCheck& c : d.checks) {
      all_passed = all_passed && c.passed;
      checks.push_back(check_json(c));
    }
    if (opt.json) {
      nlohmann::json j = device_json(i);
      j["selected"] = d.selected;
      if (opt.check) j["check"] = checks;
      std::cout << j.dump() << "\n";
      continue;
    }
    std::cout << (d.selected ? "* " : "  ") << describe_device(i) << "\n"
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
