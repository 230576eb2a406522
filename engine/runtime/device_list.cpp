// list_devices and find_device (include/snapfit/devices.h): the enumeration, the
// default choice and the self-check of engine/runtime, in public types.
#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/runtime/device_check.h"
#include "snapfit/devices.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

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

DeviceCheck public_check(const DeviceCheckResult& r) {
  DeviceCheck c;
  c.precision = r.precision;
  c.passed = r.passed;
  c.relative_error = r.relative_error;
  c.tolerance = r.tolerance;
  c.program = origin_name(r.origin);
  c.build_ms = r.build_ms;
  c.kernel_ms = r.kernel_ms;
  return c;
}

// The self-check in float, and in double where the device has it.
std::vector<DeviceCheck> check_device(const Device& device) {
  std::vector<DeviceCheck> checks;
  const ComputeContext ctx = make_compute_context(device);
  for (bool use_double : {false, true}) {
    if (use_double && !device.info.fp64) continue;
    checks.push_back(public_check(run_device_check(ctx, use_double)));
  }
  return checks;
}

}  // namespace

DeviceList list_devices(const DeviceListRequest& request) {
  const std::vector<Device> devices = enumerate_devices();
  if (devices.empty()) throw Error("no OpenCL device found: install an OpenCL driver (Debian: pocl-opencl-icd)");
  std::vector<DeviceInfo> infos;
  for (const Device& d : devices) infos.push_back(d.info);
  const std::size_t chosen = select_device_index(infos, device_spec_from(""));
  DeviceList list;
  for (const Device& d : devices) {
    ListedDevice listed;
    listed.info = d.info;
    listed.selected = static_cast<std::size_t>(d.info.index) == chosen;
    if (request.check) listed.checks = check_device(d);
    list.devices.push_back(std::move(listed));
  }
  return list;
}

bool names_device(const std::string& spec) { return !device_spec_from(spec).empty(); }

DeviceInfo find_device(const std::string& spec) { return select_device(device_spec_from(spec)).info; }

}  // namespace snapfit
