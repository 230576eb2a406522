// Program build and on-disk binary cache (engine/runtime/program_cache.h): hits, misses,
// corruption, driver refusal, key changes and build failures.
#include <doctest/doctest.h>
#include <filesystem>

#include "engine/runtime/device_check.h"
#include "engine/runtime/kernel_sources.h"
#include "engine/runtime/program_cache.h"
#include "io/cache_file.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

struct CacheFixture {
  test::TempDir dir;
  std::vector<std::string> notes;
  ComputeContext ctx = make_compute_context(select_device(""));
  ProgramCacheConfig config() {
    ProgramCacheConfig c;
    c.directory = dir.file("programs");
    c.note = [this](const std::string& m) { notes.push_back(m); };
    return c;
  }
  BuiltProgram build(const std::string& options) {
    return build_program(ctx, "device_check", kernel_source("device_check"), options, config());
  }
};

const std::string kOptions = "-D REAL=float -D WG_SIZE=64";

}  // namespace

TEST_CASE("program cache: first build compiles and writes an entry, the second loads it") {
  CacheFixture f;
  const BuiltProgram first = f.build(kOptions);
  CHECK(first.origin == ProgramOrigin::compiled);
  REQUIRE(std::filesystem::exists(first.cache_path));
  const BuiltProgram second = f.build(kOptions);
  CHECK(second.origin == ProgramOrigin::cache_hit);
  CHECK(second.cache_path == first.cache_path);
  CHECK(f.notes.empty());
  // The cached program really works: the self-check passes from a cache hit.
  const DeviceCheckResult check = run_device_check(f.ctx, false, f.config());
  CHECK(check.passed);
}

TEST_CASE("program cache: options, source and driver version are all part of the key") {
  CacheFixture f;
  const BuiltProgram a = f.build(kOptions);
  const BuiltProgram b = f.build("-D REAL=float -D WG_SIZE=32");
  CHECK(b.origin == ProgramOrigin::compiled);
  CHECK(a.cache_path != b.cache_path);

  const DeviceInfo info = f.ctx.device.info;
  const std::string source = kernel_source("device_check");
  const std::string key = program_cache_key(info, source, kOptions);
  DeviceInfo updated = info;
  updated.driver_version += "-updated";
  CHECK(program_cache_key(updated, source, kOptions) != key);
  DeviceInfo renamed = info;
  renamed.name = "cpu-" + renamed.name;  // PoCL renamed its device prefix once
  CHECK(program_cache_key(renamed, source, kOptions) != key);
  CHECK(program_cache_key(info, source + "\n// edited", kOptions) != key);
}

TEST_CASE("program cache: a corrupt entry is detected, rebuilt with a note, and then hits again") {
  CacheFixture f;
  const BuiltProgram first = f.build(kOptions);
  std::vector<char> bytes = test::read_bytes(first.cache_path);
  REQUIRE(bytes.size() > 100);

  SUBCASE("flipped payload byte") { bytes[bytes.size() / 2 + 40] ^= 0x5a; }
  SUBCASE("truncated file") { bytes.resize(bytes.size() / 2); }
  SUBCASE("zero-length file") { bytes.clear(); }
  test::write_bytes(first.cache_path, bytes);

  const BuiltProgram rebuilt = f.build(kOptions);
  CHECK(rebuilt.origin == ProgramOrigin::recompiled_after_bad_cache);
  REQUIRE(f.notes.size() == 1);
  CHECK(f.notes[0].find("corrupt") != std::string::npos);
  CHECK(f.build(kOptions).origin == ProgramOrigin::cache_hit);
}

TEST_CASE("program cache: a well-formed entry whose binary the driver refuses is never trusted") {
  CacheFixture f;
  const BuiltProgram first = f.build(kOptions);
  // Same key, valid checksum, but the payload is not a program binary.
  const std::string key = program_cache_key(f.ctx.device.info, kernel_source("device_check"), kOptions);
  const std::string garbage(4096, '\x7f');
  write_cache_file(first.cache_path, "opencl-program", 1, key, garbage.data(), garbage.size());
  const BuiltProgram rebuilt = f.build(kOptions);
  CHECK(rebuilt.origin == ProgramOrigin::recompiled_after_bad_cache);
  REQUIRE(f.notes.size() == 1);
  CHECK(f.notes[0].find("unusable") != std::string::npos);
  CHECK(run_device_check(f.ctx, false, f.config()).passed);
}

TEST_CASE("program cache: an entry from another key at the same path is stale") {
  CacheFixture f;
  const BuiltProgram first = f.build(kOptions);
  const std::string other = "payload";
  write_cache_file(first.cache_path, "opencl-program", 1, "some other key", other.data(), other.size());
  CHECK(f.build(kOptions).origin == ProgramOrigin::recompiled_after_bad_cache);
  REQUIRE(f.notes.size() == 1);
  CHECK(f.notes[0].find("stale") != std::string::npos);
}

TEST_CASE("program cache: an unwritable cache folder is a note, and the program still builds") {
  CacheFixture f;
  test::write_text(f.dir.file("programs"), "a file where the folder should be");
  const BuiltProgram built = f.build(kOptions);
  CHECK(built.origin == ProgramOrigin::compiled);
  REQUIRE(f.notes.size() == 1);
  CHECK(f.notes[0].find("not caching") != std::string::npos);
}

TEST_CASE("program build: a compile error names the kernel, the device and carries the compiler log") {
  CacheFixture f;
  const std::string broken = "__kernel void broken(__global float* x) { x[0] = undefined_symbol_xyz; }";
  try {
    build_program(f.ctx, "broken", broken, "-D REAL=float", f.config());
    FAIL("a broken kernel built");
  } catch (const Error& e) {
    const std::string message = e.what();
    CHECK(message.find("'broken'") != std::string::npos);
    CHECK(message.find(f.ctx.device.info.name) != std::string::npos);
    CHECK(message.find("undefined_symbol_xyz") != std::string::npos);  // from the compiler log
  }
  // Nothing was cached for the failed build.
  CHECK(!std::filesystem::exists(f.dir.file("programs")));
}

TEST_CASE("program build: compiler warnings are said once, naming the kernel, and a cached build says nothing") {
  CacheFixture f;
  const std::string warns = "#warning snapfit_test_warning\n__kernel void warns(__global float* x) { x[0] = 1.0f; }";
  const BuiltProgram first = build_program(f.ctx, "warns", warns, "", f.config());
  CHECK(first.origin == ProgramOrigin::compiled);
  CHECK(first.build_log.find("snapfit_test_warning") != std::string::npos);
  REQUIRE(f.notes.size() == 1);
  CHECK(f.notes[0].find("kernel 'warns' built on " + f.ctx.device.info.name + " with compiler messages") == 0);
  CHECK(f.notes[0].find("snapfit_test_warning") != std::string::npos);
  const BuiltProgram second = build_program(f.ctx, "warns", warns, "", f.config());
  CHECK(second.origin == ProgramOrigin::cache_hit);
  CHECK(second.build_log.empty());
  CHECK(f.notes.size() == 1);
  // A kernel of ours says nothing.
  const BuiltProgram check = f.build(kOptions);
  CHECK(check.build_log.empty());
}

TEST_CASE("embedded kernels: sources are carried in the binary and looked up by name") {
  CHECK(kernel_source("device_check").find("__kernel") != std::string::npos);
  CHECK_THROWS_WITH_AS(kernel_source("no_such_kernel"), doctest::Contains("device_check"), Error);
}
