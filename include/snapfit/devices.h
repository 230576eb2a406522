#pragma once
// The OpenCL devices snapfit can run on: each device's capabilities, which one a device
// spec picks (AssemblyOptions::device), and the self-check that proves a device builds
// snapfit's kernels and computes correctly, as `snapfit devices` lists them.
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

// One run of the self-check kernel: a sum computed on the device against a
// double-precision host reference.
struct DeviceCheck {
  std::string precision;  // "float" or "double"
  bool passed = false;
  double relative_error = 0;  // |device - reference| / |reference| of the total sum
  double tolerance = 0;
  std::string program;  // "compiled", "cache hit" or "recompiled (bad cache entry)"
  double build_ms = 0;
  double kernel_ms = 0;  // from the OpenCL event's profiling counters
};

struct DeviceListRequest {
  bool check = false;  // run the self-check on every device (float, and double where supported)
};

struct ListedDevice {
  DeviceInfo info;
  bool selected = false;            // the device an empty spec picks ($SNAPFIT_DEVICE, else the default)
  std::vector<DeviceCheck> checks;  // empty without DeviceListRequest::check
};

struct DeviceList {
  std::vector<ListedDevice> devices;  // in enumeration order
};

// Every device of every platform. Throws snapfit::Error when there is no OpenCL device
// at all, or when a device cannot run the self-check.
DeviceList list_devices(const DeviceListRequest& request = {});

// The device a spec picks, as AssemblyOptions::device takes it ("" takes $SNAPFIT_DEVICE,
// else PoCL's CPU device). Throws snapfit::Error listing the devices when none matches.
DeviceInfo find_device(const std::string& spec = "");

// Whether a spec names a device: the spec itself, else $SNAPFIT_DEVICE, is not empty
// (an empty one takes the default).
bool names_device(const std::string& spec);

// One line for listings: index, platform:device, name, type, platform and driver.
std::string describe_device(const DeviceInfo& info);

// PoCL exposes only its multi-threaded CPU driver by default. This asks it for the
// single-threaded one too ("basic", which runs kernels in the calling thread and suits
// the haptic loop), by setting POCL_DEVICES to "pthread basic" unless the user set it.
// Call it before the first OpenCL call.
void expose_pocl_caller_thread_driver();

}  // namespace snapfit
