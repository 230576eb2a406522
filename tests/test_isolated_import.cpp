// Work in a child process under limits (io/isolated_import.h): every way the child can
// fail is a result the parent survives.
#include <doctest/doctest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "engine/error.h"
#include "io/isolated_import.h"

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
  r = run_in_child([]() -> std::string { ::raise(SIGKILL); return ""; }, kSmall);
  CHECK(r.status == Status::out_of_memory);
  CHECK(no_children_left());
  // The parent's own memory is not limited.
  const std::vector<char> big(std::size_t(256) << 20, 'y');
  CHECK(big.back() == 'y');
}

TEST_CASE("isolated import: a crashing child is reported with its signal") {
  ChildResult r = run_in_child([]() -> std::string { ::raise(SIGSEGV); return ""; }, kSmall);
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
