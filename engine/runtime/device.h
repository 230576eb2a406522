#pragma once
// OpenCL platforms and devices: enumeration, a plain description of each device's
// capabilities, and selection by a user's device spec (--device or SNAPFIT_DEVICE).
#include <CL/opencl.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "snapfit/devices.h"

namespace snapfit {

struct Device {
  DeviceInfo info;
  cl::Device device;
};

// Every device of every platform. A platform that fails to answer is skipped; no
// platform at all gives an empty list (the caller reports it).
std::vector<Device> enumerate_devices();

// Picks a device by spec:
//   ""               the default: PoCL's CPU device if present, else the first CPU, else the
//                    first device that is not a simulator, else device 0
//   "N"              the N-th device in enumeration order
//   "P:D"            device D of platform P
//   "cpu" | "gpu" | "accelerator" | "simulator"   the first device of that type
//   anything else    the first device whose platform, name or vendor contains it (case-insensitive)
// Returns the index into `devices`; throws snapfit::Error listing the devices when none matches.
std::size_t select_device_index(const std::vector<DeviceInfo>& devices, const std::string& spec);

// The spec to use: `cli_spec` if given, else $SNAPFIT_DEVICE, else "".
std::string device_spec_from(const std::string& cli_spec);

// Enumerates and selects in one step (throws when no OpenCL device exists at all).
Device select_device(const std::string& spec);

}  // namespace snapfit
