// Device enumeration and selection (engine/runtime/device.h), and the device self-check kernel.
#include <algorithm>
#include <cstdlib>
#include <doctest/doctest.h>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "engine/runtime/device_check.h"
#include "snapfit/error.h"

using namespace snapfit;

namespace {

DeviceInfo fake(int index, int platform, int device, const std::string& platform_name, const std::string& name,
                const std::string& type) {
  DeviceInfo d;
  d.index = index;
  d.platform_index = platform;
  d.device_index = device;
  d.platform_name = platform_name;
  d.platform_version = platform_name == "Portable Computing Language" ? "OpenCL 3.0 PoCL 3.1" : "OpenCL 3.0";
  d.name = name;
  d.vendor = type == "gpu" ? "NVIDIA Corporation" : "AuthenticAMD";
  d.type = type;
  return d;
}

// A machine with a GPU first, an Intel CPU runtime, then PoCL's CPU device.
std::vector<DeviceInfo> three_devices() {
  return {fake(0, 0, 0, "NVIDIA CUDA", "NVIDIA H100 80GB HBM3", "gpu"),
          fake(1, 1, 0, "Intel(R) OpenCL", "AMD EPYC 9454", "cpu"),
          fake(2, 2, 0, "Portable Computing Language", "cpu-skylake-avx512-AMD EPYC", "cpu")};
}

}  // namespace

TEST_CASE("device selection: the default is PoCL's CPU device, wherever it is listed") {
  CHECK(select_device_index(three_devices(), "") == 2);
  auto no_pocl = three_devices();
  no_pocl.pop_back();
  CHECK(select_device_index(no_pocl, "") == 1);  // then the first CPU
  std::vector<DeviceInfo> gpu_only = {three_devices()[0]};
  CHECK(select_device_index(gpu_only, "") == 0);  // then device 0
  // PoCL listing its single-threaded driver first: the multi-threaded one is the default.
  const std::vector<DeviceInfo> pocl_two = {
      fake(0, 0, 0, "Portable Computing Language", "basic-skylake-avx512-AMD EPYC", "cpu"),
      fake(1, 0, 1, "Portable Computing Language", "pthread-skylake-avx512-AMD EPYC", "cpu")};
  CHECK(select_device_index(pocl_two, "") == 1);
  CHECK(select_device_index({pocl_two[0]}, "") == 0);  // basic alone is still PoCL's CPU device
}

TEST_CASE("device selection: a simulator (Oclgrind) is chosen only when named or alone") {
  // Oclgrind claims CPU, GPU and accelerator at once: enumeration calls it a simulator,
  // which the default and the other type specs pass over, wherever it is listed.
  std::vector<DeviceInfo> devices = three_devices();
  for (DeviceInfo& d : devices) ++d.index, ++d.platform_index;
  devices.insert(devices.begin(), fake(0, 0, 0, "Oclgrind", "Oclgrind Simulator", "simulator"));
  CHECK(devices[0].is_simulator());
  CHECK(!devices[1].is_simulator());
  CHECK(select_device_index(devices, "") == 3);
  CHECK(select_device_index(devices, "gpu") == 1);
  CHECK(select_device_index(devices, "cpu") == 2);
  CHECK(select_device_index(devices, "oclgrind") == 0);
  CHECK(select_device_index(devices, "simulator") == 0);
  const std::vector<DeviceInfo> simulator_and_gpu = {devices[0], devices[1]};
  CHECK(select_device_index(simulator_and_gpu, "") == 1);  // not a CPU, but not a simulator
  CHECK(select_device_index({devices[0]}, "") == 0);       // alone: the only device there is
  CHECK_THROWS_WITH_AS(select_device_index({devices[0]}, "gpu"), doctest::Contains("no gpu device"), Error);
}

TEST_CASE("device selection: by index, platform:device, type and name substring") {
  const auto devices = three_devices();
  CHECK(select_device_index(devices, "1") == 1);
  CHECK(select_device_index(devices, "0:0") == 0);
  CHECK(select_device_index(devices, "2:0") == 2);
  CHECK(select_device_index(devices, "gpu") == 0);
  CHECK(select_device_index(devices, "GPU") == 0);
  CHECK(select_device_index(devices, "cpu") == 1);
  CHECK(select_device_index(devices, "h100") == 0);
  CHECK(select_device_index(devices, "portable") == 2);
  CHECK(select_device_index(devices, "  Intel ") == 1);
}

TEST_CASE("device selection: a spec that matches nothing names the spec and lists the devices") {
  const auto devices = three_devices();
  CHECK_THROWS_WITH_AS(select_device_index(devices, "7"), doctest::Contains("H100"), Error);
  CHECK_THROWS_WITH_AS(select_device_index(devices, "3:1"), doctest::Contains("3:1"), Error);
  CHECK_THROWS_WITH_AS(select_device_index(devices, "accelerator"), doctest::Contains("no accelerator device"), Error);
  CHECK_THROWS_WITH_AS(select_device_index(devices, "radeon"), doctest::Contains("'radeon'"), Error);
  CHECK_THROWS_WITH_AS(select_device_index({}, ""), doctest::Contains("no OpenCL device"), Error);
}

TEST_CASE("device selection: SNAPFIT_DEVICE applies when --device is not given") {
  ::setenv("SNAPFIT_DEVICE", "gpu", 1);
  CHECK(device_spec_from("") == "gpu");
  CHECK(device_spec_from("cpu") == "cpu");
  ::unsetenv("SNAPFIT_DEVICE");
  CHECK(device_spec_from("") == "");
}

TEST_CASE("device enumeration: this machine has an OpenCL device with sane capabilities") {
  const std::vector<Device> devices = enumerate_devices();
  REQUIRE_MESSAGE(!devices.empty(), "no OpenCL device: is pocl-opencl-icd installed?");
  for (const Device& d : devices) {
    CHECK(!d.info.name.empty());
    CHECK(!d.info.driver_version.empty());
    CHECK(d.info.compute_units > 0);
    CHECK(d.info.global_memory_bytes > 0);
    CHECK(d.info.max_work_group_size > 0);
  }
  const Device chosen = select_device("");
  MESSAGE("default device: " << describe_device(chosen.info));
  // The default is a CPU wherever one exists (PoCL's first); a machine without one (a GPU
  // node without PoCL) gets a device that is not a simulator, when it has one.
  const bool any_cpu = std::any_of(devices.begin(), devices.end(), [](const Device& d) { return d.info.type == "cpu"; });
  const bool any_real = std::any_of(devices.begin(), devices.end(), [](const Device& d) { return d.info.type != "simulator"; });
  if (any_cpu)
    CHECK(chosen.info.type == "cpu");
  else if (any_real)
    CHECK(chosen.info.type != "simulator");
}

TEST_CASE("device self-check: every device computes the reference sum, in float and (where supported) double") {
  ProgramCacheConfig no_cache;  // always compile: this checks the compiler, not the cache
  for (const Device& d : enumerate_devices()) {
    const ComputeContext ctx = make_compute_context(d);
    const DeviceCheckResult f = run_device_check(ctx, false, no_cache);
    CHECK_MESSAGE(f.passed, d.info.name << " float: relative error " << f.relative_error << " > " << f.tolerance);
    CHECK(f.relative_error < 1e-3);  // the float sum carries ~7 digits; a broken reduction is off by O(1)
    if (d.info.fp64) {
      const DeviceCheckResult dbl = run_device_check(ctx, true, no_cache);
      CHECK_MESSAGE(dbl.passed, d.info.name << " double: relative error " << dbl.relative_error);
      CHECK(dbl.relative_error < 1e-10);
    } else {
      CHECK_THROWS_AS(run_device_check(ctx, true, no_cache), Error);
    }
  }
}

TEST_CASE("device self-check: a smaller sum passes too, and fewer than 2 points are refused") {
  const ComputeContext ctx = make_compute_context(select_device(""));
  ProgramCacheConfig no_cache;
  const DeviceCheckResult small = run_device_check(ctx, false, no_cache, 20 * 256);
  CHECK_MESSAGE(small.passed, "relative error " << small.relative_error << " > " << small.tolerance);
  CHECK_THROWS_WITH_AS(run_device_check(ctx, false, no_cache, 1), doctest::Contains("at least 2 points"), Error);
}

TEST_CASE("device: PoCL's basic driver runs kernels in the caller's thread, its pthread driver does not") {
  snapfit::DeviceInfo d;
  d.platform_name = "Portable Computing Language";
  d.name = "basic-skylake-avx512-AMD EPYC";
  CHECK(d.runs_in_caller_thread());
  d.name = "pthread-skylake-avx512-AMD EPYC";
  CHECK(!d.runs_in_caller_thread());
  d.platform_name = "NVIDIA CUDA";
  d.platform_version = "OpenCL 3.0 CUDA 12.4";
  d.name = "basic GPU";
  CHECK(!d.runs_in_caller_thread());
}
