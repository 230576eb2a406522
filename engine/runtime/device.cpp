#include "engine/runtime/device.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <sstream>

#include "snapfit/error.h"

namespace snapfit {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

// OpenCL strings may carry a trailing NUL; user specs may carry spaces.
std::string trimmed(std::string s) {
  auto blank = [](char c) { return c == '\0' || std::isspace(static_cast<unsigned char>(c)); };
  while (!s.empty() && blank(s.back())) s.pop_back();
  std::size_t first = 0;
  while (first < s.size() && blank(s[first])) ++first;
  return s.substr(first);
}

std::string type_name(cl_device_type type) {
  if (type & CL_DEVICE_TYPE_GPU) return "gpu";
  if (type & CL_DEVICE_TYPE_CPU) return "cpu";
  if (type & CL_DEVICE_TYPE_ACCELERATOR) return "accelerator";
  return "other";
}

bool is_unsigned_integer(const std::string& s) {
  return !s.empty() && s.size() < 9 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

std::string device_list(const std::vector<DeviceInfo>& devices) {
  std::string out;
  for (const DeviceInfo& d : devices) out += "\n  " + describe_device(d);
  return out.empty() ? " (none)" : out;
}

// Oclgrind (an OpenCL device simulator) reports CPU, GPU and accelerator at once.
bool is_oclgrind_platform(const std::string& platform_name) { return lower(platform_name) == "oclgrind"; }

}  // namespace

bool DeviceInfo::is_pocl() const {
  return lower(platform_name).find("portable computing language") != std::string::npos ||
         lower(platform_version).find("pocl") != std::string::npos;
}

void expose_pocl_caller_thread_driver() { setenv("POCL_DEVICES", "pthread basic", 0); }

bool DeviceInfo::runs_in_caller_thread() const {
  // PoCL names its devices after the driver: "basic-<cpu>", "pthread-<cpu>", ...
  return is_pocl() && lower(name).rfind("basic", 0) == 0;
}

std::vector<Device> enumerate_devices() {
  std::vector<Device> out;
  std::vector<cl::Platform> platforms;
  // No ICD at all makes clGetPlatformIDs fail with CL_PLATFORM_NOT_FOUND_KHR.
  if (cl::Platform::get(&platforms) != CL_SUCCESS) return out;
  for (std::size_t p = 0; p < platforms.size(); ++p) {
    std::vector<cl::Device> devices;
    try {
      platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
    } catch (const cl::Error&) {
      continue;  // a platform with no usable device
    }
    for (std::size_t d = 0; d < devices.size(); ++d) {
      Device dev;
      dev.device = devices[d];
      DeviceInfo& info = dev.info;
      info.index = static_cast<int>(out.size());
      info.platform_index = static_cast<int>(p);
      info.device_index = static_cast<int>(d);
      info.platform_name = trimmed(platforms[p].getInfo<CL_PLATFORM_NAME>());
      info.platform_version = trimmed(platforms[p].getInfo<CL_PLATFORM_VERSION>());
      info.name = trimmed(devices[d].getInfo<CL_DEVICE_NAME>());
      info.vendor = trimmed(devices[d].getInfo<CL_DEVICE_VENDOR>());
      info.type =
          is_oclgrind_platform(info.platform_name) ? "simulator" : type_name(devices[d].getInfo<CL_DEVICE_TYPE>());
      info.device_version = trimmed(devices[d].getInfo<CL_DEVICE_VERSION>());
      info.driver_version = trimmed(devices[d].getInfo<CL_DRIVER_VERSION>());
      info.compute_units = devices[d].getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
      info.global_memory_bytes = devices[d].getInfo<CL_DEVICE_GLOBAL_MEM_SIZE>();
      info.local_memory_bytes = devices[d].getInfo<CL_DEVICE_LOCAL_MEM_SIZE>();
      info.max_alloc_bytes = devices[d].getInfo<CL_DEVICE_MAX_MEM_ALLOC_SIZE>();
      info.max_work_group_size = devices[d].getInfo<CL_DEVICE_MAX_WORK_GROUP_SIZE>();
      info.fp64 = devices[d].getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
      out.push_back(std::move(dev));
    }
  }
  return out;
}

std::size_t select_device_index(const std::vector<DeviceInfo>& devices, const std::string& spec_in) {
  if (devices.empty()) {
    throw Error("no OpenCL device found: install an OpenCL driver (Debian: pocl-opencl-icd) and check `clinfo -l`");
  }
  const std::string spec = lower(trimmed(spec_in));
  if (spec.empty()) {
    // PoCL's multi-threaded CPU driver first (its single-threaded "basic" driver uses one core).
    for (std::size_t i = 0; i < devices.size(); ++i)
      if (devices[i].is_pocl() && devices[i].type == "cpu" && !devices[i].runs_in_caller_thread()) return i;
    for (std::size_t i = 0; i < devices.size(); ++i)
      if (devices[i].is_pocl() && devices[i].type == "cpu") return i;
    for (std::size_t i = 0; i < devices.size(); ++i)
      if (devices[i].type == "cpu") return i;
    for (std::size_t i = 0; i < devices.size(); ++i)
      if (!devices[i].is_simulator()) return i;
    return 0;
  }
  if (is_unsigned_integer(spec)) {
    const std::size_t n = std::stoul(spec);
    if (n < devices.size()) return n;
    throw Error("device " + spec + " does not exist; devices are:" + device_list(devices));
  }
  const std::size_t colon = spec.find(':');
  if (colon != std::string::npos && is_unsigned_integer(spec.substr(0, colon)) &&
      is_unsigned_integer(spec.substr(colon + 1))) {
    const int p = std::stoi(spec.substr(0, colon));
    const int d = std::stoi(spec.substr(colon + 1));
    for (std::size_t i = 0; i < devices.size(); ++i)
      if (devices[i].platform_index == p && devices[i].device_index == d) return i;
    throw Error("device " + spec + " (platform:device) does not exist; devices are:" + device_list(devices));
  }
  if (spec == "cpu" || spec == "gpu" || spec == "accelerator" || spec == "simulator") {
    for (std::size_t i = 0; i < devices.size(); ++i)
      if (devices[i].type == spec) return i;
    throw Error("no " + spec + " device; devices are:" + device_list(devices));
  }
  for (std::size_t i = 0; i < devices.size(); ++i) {
    const std::string haystack = lower(devices[i].platform_name + " " + devices[i].name + " " + devices[i].vendor);
    if (haystack.find(spec) != std::string::npos) return i;
  }
  throw Error("no device matches '" + spec_in + "'; devices are:" + device_list(devices));
}

std::string device_spec_from(const std::string& cli_spec) {
  if (!cli_spec.empty()) return cli_spec;
  const char* env = std::getenv("SNAPFIT_DEVICE");
  return env ? std::string(env) : std::string();
}

Device select_device(const std::string& spec) {
  std::vector<Device> devices;
  try {
    devices = enumerate_devices();
  } catch (const cl::Error& e) {
    throw Error(std::string("OpenCL device enumeration failed: ") + e.what() + " (error " + std::to_string(e.err()) +
                ")");
  }
  std::vector<DeviceInfo> infos;
  for (const Device& d : devices) infos.push_back(d.info);
  return devices[select_device_index(infos, spec)];
}

std::string describe_device(const DeviceInfo& d) {
  std::ostringstream out;
  out << "[" << d.index << "] " << d.platform_index << ":" << d.device_index << " " << d.name << " (" << d.type << ", "
      << d.platform_name << ", driver " << d.driver_version << ")";
  return out.str();
}

}  // namespace snapfit
