// Work in a child process under limits (io/isolated_import.h), and load_mesh's import
// child (io/mesh_load.cpp): every way the child can fail is a result the
// parent survives, and a large mesh comes back bit for bit.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <doctest/doctest.h>
#include <signal.h>
#include <stdexcept>
#include <string>
#include <sys/wait.h>
#include <unistd.h>
#include <vector>

#include "io/isolated_import.h"
#include "io/mesh_export.h"
#include "io/mesh_load.h"
#include "snapfit/error.h"
#include "tests/test_meshes.h"
#include "tests/test_support.h"

using namespace snapfit;
using Status = ChildResult::Status;

namespace {

const ChildLimits kSmall{64, 2, 10};  // 64 MiB, 2 CPU seconds, 10 s

// No child of this process is left, running or zombie.
bool no_children_left() { return ::waitpid(-1, nullptr, WNOHANG) == -1 && errno == ECHILD; }

}  // namespace

TEST_CASE("isolated import: the child's bytes and error messages come back unchanged") {
  // 64 MiB: larger than a pipe's buffer, so the parent must read while the child writes.
  std::string big(64u << 20, '\0');
  for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>(i * 2654435761u >> 24);
  ChildResult r = run_in_child([&] { return big; }, ChildLimits{256, 10, 30});
  REQUIRE(r.status == Status::ok);
  CHECK(r.bytes == big);
  r = run_in_child([] { return std::string(); }, kSmall);
  CHECK(r.status == Status::ok);
  CHECK(r.bytes.empty());

  r = run_in_child([]() -> std::string { throw Error("part.stl: face 3 refers to vertex 9"); }, kSmall);
  CHECK(r.status == Status::error);
  CHECK(r.bytes == "part.stl: face 3 refers to vertex 9");
  r = run_in_child([]() -> std::string { throw std::out_of_range("vector::at"); }, kSmall);
  CHECK(r.status == Status::exception);
  CHECK(r.bytes == "vector::at");
  CHECK(no_children_left());
}

TEST_CASE("isolated import: the child's stdout is /dev/null, so nothing it flushes reaches the parent's output") {
  const ChildResult r = run_in_child(
      [] {
        std::printf("from the child\n");
        std::fflush(stdout);
        char target[256] = {};
        const ssize_t n = ::readlink("/proc/self/fd/1", target, sizeof target - 1);
        return std::string(target, n > 0 ? static_cast<std::size_t>(n) : 0);
      },
      kSmall);
  REQUIRE(r.status == Status::ok);
  CHECK(r.bytes == "/dev/null");
}

TEST_CASE("isolated import: a child past its memory limit is reported, the parent goes on") {
  // One allocation larger than the limit, and many small ones that add up past it.
  ChildResult r = run_in_child([] { return std::string(std::size_t(1) << 30, 'x'); }, kSmall);
  CHECK(r.status == Status::out_of_memory);
  r = run_in_child(
      [] {
        std::vector<std::vector<char>> blocks;
        for (;;) blocks.emplace_back(1 << 20, 'x');  // touched, so the memory is real
        return std::string();
      },
      kSmall);
  CHECK(r.status == Status::out_of_memory);
  // std::bad_alloc out of a noexcept function (std::terminate), and SIGKILL (what the
  // kernel's OOM killer sends) count as running out of memory too.
  r = run_in_child(
      []() -> std::string {
        []() noexcept { std::vector<char> v(std::size_t(1) << 30); }();
        return "";
      },
      kSmall);
  CHECK(r.status == Status::out_of_memory);
  r = run_in_child(
      []() -> std::string {
        ::raise(SIGKILL);
        return "";
      },
      kSmall);
  CHECK(r.status == Status::out_of_memory);
  CHECK(no_children_left());
  // The parent's own memory is not limited.
  const std::vector<char> big(std::size_t(256) << 20, 'y');
  CHECK(big.back() == 'y');
}

TEST_CASE("isolated import: a crashing child is reported with its signal") {
  ChildResult r = run_in_child(
      []() -> std::string {
        ::raise(SIGSEGV);
        return "";
      },
      kSmall);
  CHECK(r.status == Status::crashed);
  CHECK(r.signal == SIGSEGV);
  r = run_in_child([]() -> std::string { std::abort(); }, kSmall);
  CHECK(r.status == Status::crashed);
  CHECK(r.signal == SIGABRT);
  // Exiting without a reply is a malformed reply.
  r = run_in_child([]() -> std::string { ::_exit(3); }, kSmall);
  CHECK(r.status == Status::bad_reply);
  CHECK(r.bytes == "exited with status 3 after a malformed reply (0 bytes)");
  CHECK(no_children_left());
}

TEST_CASE("isolated import: a child past its CPU or wall-clock time is killed") {
  ChildResult r = run_in_child(
      []() -> std::string {
        volatile unsigned long spin = 0;
        for (;;) spin = spin + 1;
      },
      ChildLimits{64, 1, 30});
  CHECK(r.status == Status::timed_out);
  // A child that waits without using the CPU is killed at the wall-clock limit.
  r = run_in_child(
      []() -> std::string {
        ::pause();
        return "";
      },
      ChildLimits{64, 10, 0.3});
  CHECK(r.status == Status::timed_out);
  CHECK(no_children_left());
}

TEST_CASE("isolated import: a large mesh comes back from the import child bit for bit") {
  test::TempDir dir;
  const std::string file = dir.file("soup.stl");
  write_stl(test::random_soup(200000, 7, 50.0, 1.0), file);
  Mesh in_process;
  {
    test::EnvScope env("SNAPFIT_IMPORT_MEMORY_MIB", "inprocess");
    in_process = load_mesh(file, 0.1);
  }
  test::EnvScope env("SNAPFIT_IMPORT_MEMORY_MIB", nullptr);  // the default: a child
  const Mesh child = load_mesh(file, 0.1);
  REQUIRE(child.triangles.size() == 200000);
  REQUIRE(child.vertices.size() == in_process.vertices.size());
  REQUIRE(child.triangles.size() == in_process.triangles.size());
  CHECK(std::memcmp(child.vertices.data(), in_process.vertices.data(),
                    child.vertices.size() * sizeof(Eigen::Vector3d)) == 0);
  CHECK(std::memcmp(child.triangles.data(), in_process.triangles.data(),
                    child.triangles.size() * sizeof(Eigen::Vector3i)) == 0);
  CHECK(no_children_left());
}

TEST_CASE("isolated import: SNAPFIT_IMPORT_MEMORY_MIB sets the import child's memory limit") {
  test::TempDir dir;
  const std::string file = dir.file("peg.obj");
  write_obj(test::peg_mesh(), file);
  for (const char* value : {"inprocess", "0", "512"}) {
    test::EnvScope env("SNAPFIT_IMPORT_MEMORY_MIB", value);
    CHECK(load_mesh(file).triangles.size() == test::peg_mesh().triangles.size());
  }
  {
    // The fuzzed .x file on which Assimp allocates 4.2 GB: the error names the limit.
    const std::string blowup = dir.file("blowup.x");
    test::write_bytes(blowup,
                      test::read_bytes(std::string(SNAPFIT_SOURCE_DIR) + "/tests/data/fuzz/x_memory_blowup.bin"));
    test::EnvScope env("SNAPFIT_IMPORT_MEMORY_MIB", "100");
    CHECK_THROWS_WITH_AS(
        load_mesh(blowup),
        doctest::Contains((blowup + ": cannot read mesh: the importer exceeded its memory limit of 100 MiB").c_str()),
        Error);
  }
  for (const char* bad : {"", "lots", "-5", "1.5", "99999999999"}) {
    test::EnvScope env("SNAPFIT_IMPORT_MEMORY_MIB", bad);
    CHECK_THROWS_WITH_AS(load_mesh(file), doctest::Contains("SNAPFIT_IMPORT_MEMORY_MIB must be a whole number of MiB"),
                         Error);
  }
}
