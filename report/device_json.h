#pragma once
// An OpenCL device's description as the JSON object that `snapfit devices --json` prints
// and the benchmarks' reports carry.
#include <nlohmann/json.hpp>

#include "snapfit/devices.h"

namespace snapfit {

// index, platform_index, device_index, platform, name, vendor, type, device_version,
// driver_version, compute_units, global/local memory and max allocation in bytes,
// max_work_group_size and fp64.
nlohmann::json device_json(const DeviceInfo& info);

}  // namespace snapfit
