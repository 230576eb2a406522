#pragma once
// OpenCL platforms and devices: enumeration, a plain description of each device's
// capabilities, and selection by a user's device spec (--device or SNAPFIT_DEVICE).
#include <CL/opencl.hpp>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace snapfit {

struct DeviceInfo {
  int index = 0;  // position in enumeration order (what `snapfit devices` lists)
  int platform_index = 0;
  int device_index = 0;  // position within its platform
  std::string platform_name;
  std::string platform_version;
  std::string name;
  std::string vendor;
  // "cpu", "gpu", "accelerator", "simulator" (Oclgrind, which claims every type but
  // interprets kernels one work-item at a time: for checks, never picked unless named) or "other"
  std::string type;
  std::string device_version;
  std::string driver_version;
  unsigned compute_units = 0;
  std::uint64_t global_memory_bytes = 0;
  std::uint64_t local_memory_bytes = 0;
  std::uint64_t max_alloc_bytes = 0;
  std::size_t max_work_group_size = 0;
  bool fp64 = false;
  bool is_pocl() const;
  bool is_simulator() const { return type == "simulator"; }
  // The runtime runs kernels in the thread that waits for them, with no worker threads
  // to wake (PoCL's "basic" driver).
  bool runs_in_caller_thread() const;
};

struct Device {
  DeviceInfo info;
  cl::Device device;
};

// PoCL exposes only its multi-threaded CPU driver by default. This asks it for the
// single-threaded one too ("basic", which runs kernels in the calling thread and suits
// the haptic loop: scheduler/device_choice.h loop_device), by setting POCL_DEVICES to
// "pthread basic" unless the user set it. Call it before the first OpenCL call.
void expose_pocl_caller_thread_driver();

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

// One line per device for listings.
std::string describe_device(const DeviceInfo& info);

}  // namespace snapfit
