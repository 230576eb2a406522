#include "report/device_json.h"

namespace snapfit {

nlohmann::json device_json(const DeviceInfo& info) {
  return {{"index", info.index},
          {"platform_index", info.platform_index},
          {"device_index", info.device_index},
          {"platform", info.platform_name},
          {"name", info.name},
          {"vendor", info.vendor},
          {"type", info.type},
          {"device_version", info.device_version},
          {"driver_version", info.driver_version},
          {"compute_units", info.compute_units},
          {"global_memory_bytes", info.global_memory_bytes},
          {"max_alloc_bytes", info.max_alloc_bytes},
          {"local_memory_bytes", info.local_memory_bytes},
          {"max_work_group_size", info.max_work_group_size},
          {"fp64", info.fp64}};
}

}  // namespace snapfit
