#include "engine/runtime/program_cache.h"

#include <chrono>
#include <filesystem>
#include <iostream>

#include "core/hash.h"
#include "io/cache_file.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr std::uint32_t kProgramCacheVersion = 1;

double ms_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

// The compiler's log of the last build on ctx's device, trimmed; "" when it said nothing.
std::string build_log(const cl::Program& program) {
  std::string log;
  try {
    for (const auto& entry : program.getBuildInfo<CL_PROGRAM_BUILD_LOG>()) log += entry.second;
  } catch (const cl::Error&) {
    return "";
  }
  const std::size_t first = log.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return log.substr(first, log.find_last_not_of(" \t\r\n") - first + 1);
}

std::string build_failure(const std::string& name, const DeviceInfo& device, const std::string& options,
                          const cl::Program& program, const cl::Error& e) {
  std::string log = build_log(program);
  if (log.empty()) log = "(no build log available)";
  return "kernel '" + name + "' failed to build on device " + device.name + " (driver " + device.driver_version +
         ", options '" + options + "'): " + e.what() + " error " + std::to_string(e.err()) + "\n" + log;
}

cl::Program compile_from_source(const ComputeContext& ctx, const std::string& name, const std::string& source,
                                const std::string& options) {
  cl::Program program(ctx.context, source);
  try {
    program.build({ctx.device.device}, options.c_str());
  } catch (const cl::Error& e) {
    throw Error(build_failure(name, ctx.device.info, options, program, e));
  }
  return program;
}

// Returns a built program from a binary, or a null program when the driver refuses it.
cl::Program program_from_binary(const ComputeContext& ctx, const std::vector<unsigned char>& binary,
                                const std::string& options, std::string& why) {
  try {
    std::vector<cl_int> status;
    cl::Program program(ctx.context, {ctx.device.device}, cl::Program::Binaries{binary}, &status);
    if (!status.empty() && status[0] != CL_SUCCESS) {
      why = "driver refused the binary (status " + std::to_string(status[0]) + ")";
      return cl::Program();
    }
    program.build({ctx.device.device}, options.c_str());
    return program;
  } catch (const cl::Error& e) {
    why = std::string("driver refused the binary: ") + e.what() + " error " + std::to_string(e.err());
    return cl::Program();
  }
}

}  // namespace

ProgramCacheConfig default_program_cache() {
  ProgramCacheConfig config;
  config.directory = (std::filesystem::path(cache_root()) / "programs").string();
  config.note = [](const std::string& message) { std::cerr << "snapfit: " << message << "\n"; };
  return config;
}

std::string program_cache_key(const DeviceInfo& device, const std::string& source, const std::string& options) {
  return "platform=" + device.platform_name + " " + device.platform_version + "|device=" + device.name +
         "|vendor=" + device.vendor + "|device_version=" + device.device_version + "|driver=" + device.driver_version +
         "|source_fnv1a64=" + hex64(fnv1a64(source)) + "|options=" + options;
}

BuiltProgram build_program(const ComputeContext& ctx, const std::string& name, const std::string& source,
                           const std::string& options, const ProgramCacheConfig& cache) {
  const auto start = std::chrono::steady_clock::now();
  auto note = [&](const std::string& m) {
    if (cache.note) cache.note(m);
  };
  BuiltProgram built;
  // A build that succeeded with something to say (warnings): said once, naming the kernel.
  auto keep_log = [&] {
    built.build_log = build_log(built.program);
    if (!built.build_log.empty())
      note("kernel '" + name + "' built on " + ctx.device.info.name + " with compiler messages:\n" + built.build_log);
  };
  if (cache.directory.empty()) {
    built.program = compile_from_source(ctx, name, source, options);
    keep_log();
    built.build_ms = ms_since(start);
    return built;
  }
  const std::string key = program_cache_key(ctx.device.info, source, options);
  built.cache_path = (std::filesystem::path(cache.directory) / (name + "-" + hex64(fnv1a64(key)) + ".bin")).string();

  const CacheRead entry = read_cache_file(built.cache_path, "opencl-program", kProgramCacheVersion, key);
  if (entry.status == CacheStatus::hit) {
    std::string why;
    built.program = program_from_binary(ctx, entry.payload, options, why);
    if (built.program()) {
      built.origin = ProgramOrigin::cache_hit;
      built.build_ms = ms_since(start);
      return built;
    }
    note("program cache entry " + built.cache_path + " is unusable (" + why + "); rebuilding from source");
    built.origin = ProgramOrigin::recompiled_after_bad_cache;
  } else if (entry.status != CacheStatus::missing) {
    note("program cache entry " + built.cache_path + " is " +
         (entry.status == CacheStatus::corrupt ? "corrupt" : "stale") + " (" + entry.reason +
         "); rebuilding from source");
    built.origin = ProgramOrigin::recompiled_after_bad_cache;
  }

  built.program = compile_from_source(ctx, name, source, options);
  keep_log();
  try {
    const auto binaries = built.program.getInfo<CL_PROGRAM_BINARIES>();
    if (!binaries.empty() && !binaries[0].empty()) {
      write_cache_file(built.cache_path, "opencl-program", kProgramCacheVersion, key, binaries[0].data(),
                       binaries[0].size());
    }
  } catch (const Error& e) {
    note(std::string("not caching the program: ") + e.what());
  } catch (const cl::Error& e) {
    note(std::string("not caching the program: the driver gave no binary (") + e.what() + ")");
  }
  built.build_ms = ms_since(start);
  return built;
}

}  // namespace snapfit
