// Oclgrind as a device of snapfit's (docs/portability.md): listed by `snapfit devices`
// as a simulator, never the default, selected by `--device oclgrind`; the device
// self-check under every check; and the two defects of Oclgrind 21.10's
// uninitialised-value plugin that keep that check off for most kernels, each on its
// minimal reproducer (tests/data/oclgrind), so that a fixed Oclgrind fails here and says
// to turn the check back on.
#include <doctest/doctest.h>
#include <string>

#include "engine/runtime/device_check.h"
#include "tests/oclgrind/oclgrind_support.h"
#include "tests/test_support.h"

namespace snapfit::test {
namespace {

std::string cli() { return SNAPFIT_CLI_PATH; }

std::string reproducer(const std::string& name) {
  return std::string(SNAPFIT_OCLGRIND_RUN_KERNEL_PATH) + " " + SNAPFIT_SOURCE_DIR + "/tests/data/oclgrind/" + name;
}

}  // namespace

TEST_CASE(
    "oclgrind: snapfit devices lists Oclgrind as a simulator, not the default, and --device oclgrind selects it") {
  const Command list = run_command(cli() + " devices --json", false);
  REQUIRE(list.status == 0);
  const std::string::size_type line = list.output.find("\"platform\":\"Oclgrind\"");
  REQUIRE_MESSAGE(line != std::string::npos, list.output);
  const std::string entry =
      list.output.substr(list.output.rfind('{', line), list.output.find('}', line) + 1 - list.output.rfind('{', line));
  CHECK(entry.find("\"type\":\"simulator\"") != std::string::npos);
  CHECK(entry.find("\"selected\":false") != std::string::npos);

  // Descriptors of a small part through the CLI, on the device the spec names.
  const TempDir dir;
  write_text(dir.file("scene.json"), R"({
    "snapfit_scene": 1, "name": "small peg", "units": "mm",
    "part1": {"name": "block", "procedural": {"type": "hole_block", "peg_radius": 0.6, "clearance": 0.1,
              "hole_depth": 1.2, "width": 2.4, "height": 1.6, "segments": 8}},
    "part2": {"name": "peg", "procedural": {"type": "peg", "radius": 0.6, "length": 2, "segments": 8}},
    "descriptor": {"kind": "indicator"},
    "grid": {"spacing": 0.8, "padding": 0.8}
  })");
  const std::string env = "SNAPFIT_CACHE_DIR=" + dir.file("cache") + " ";
  const Command fields = run_command(env + cli() + " fields " + dir.file("scene.json") + " --part 2 --device oclgrind");
  CHECK_MESSAGE(fields.status == 0, fields.output);
  CHECK_MESSAGE(fields.output.find("on Oclgrind Simulator") != std::string::npos, fields.output);
}

TEST_CASE("oclgrind: the device self-check, float and double, under every check including uninitialised values") {
  const OclgrindChecks checks = checks_for({"device_check"});
  REQUIRE(checks.uninitialized);
  OclgrindSession session(checks);
  for (const bool use_double : {false, true}) {
    // 20 work-groups of 256 items (the engine's group size wherever the device allows it).
    const DeviceCheckResult r = run_device_check(session.context(), use_double, ProgramCacheConfig{}, 20 * 256);
    CHECK_MESSAGE(r.passed, r.precision << ": relative error " << r.relative_error << " > " << r.tolerance);
    const std::string reports = session.take_reports();
    CHECK_MESSAGE(reports.empty(), "device_check (" << r.precision << "): Oclgrind reported:\n" << reports);
  }
}

TEST_CASE("oclgrind: its uninitialised-value plugin crashes on undef shuffle lanes, a valid kernel it runs without") {
  // Without the plugin: the kernel's value (2^2 + 3^2 + 4^2 on every work-item).
  const Command plain = run_command(reproducer("undef_shuffle_lanes.cl"), false);
  CHECK(plain.status == 0);
  CHECK(plain.output == "29\n29\n29\n29\n");
  // With it: SIGSEGV (the shell reports 128 + 11). If this fails, Oclgrind is fixed: take
  // the kernels whose defect names undef_shuffle_lanes.cl off uninitialized_check_defects.
  const Command checked = run_command("OCLGRIND_UNINITIALIZED=1 " + reproducer("undef_shuffle_lanes.cl"));
  CHECK_MESSAGE(checked.status == 128 + 11, "exit status " << checked.status << ":\n" << checked.output);
}

TEST_CASE("oclgrind: its uninitialised-value plugin stops on freeze, in a valid kernel it runs without") {
  const Command plain = run_command(reproducer("freeze.cl"), false);
  CHECK(plain.status == 0);
  CHECK(plain.output == "0.5\n1\n1\n1.5\n");  // n / 3 + (n % 3) / 2 for n = 1 .. 4
  // With it: the plugin's fatal error, and the kernel abandoned. If this fails, Oclgrind
  // runs freeze: take the kernels whose defect names freeze.cl off the list.
  const Command checked = run_command("OCLGRIND_UNINITIALIZED=1 " + reproducer("freeze.cl"));
  CHECK_MESSAGE(checked.output.find("Unsupported instruction: freeze") != std::string::npos, checked.output);
}

}  // namespace snapfit::test
