// Work in a child process under limits (io/isolated_import.h).
#include "io/isolated_import.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <exception>
#include <fcntl.h>
#include <fstream>
#include <new>
#include <poll.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "snapfit/error.h"

namespace snapfit {
namespace {

// Reply, child -> parent: one tag byte, the payload size (uint64, host order), the
// payload; then the child exits with status 0. Anything else is a malformed reply.
constexpr char kTagOk = 'O', kTagError = 'E', kTagException = 'X';
constexpr std::size_t kHeaderBytes = 1 + sizeof(std::uint64_t);
// Exit status of a child that ran out of memory (std::bad_alloc, also one that escaped
// into std::terminate), and of one that could not write its reply.
constexpr int kExitOutOfMemory = 86, kExitWriteFailed = 87;

std::string errno_text(const std::string& what) { return what + ": " + std::strerror(errno); }

// Writes all bytes, retrying on EINTR and short writes; allocates nothing.
bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

bool write_reply(int fd, char tag, const std::string& payload) {
  char header[kHeaderBytes];
  header[0] = tag;
  const std::uint64_t size = payload.size();
  std::memcpy(header + 1, &size, sizeof size);
  return write_all(fd, header, kHeaderBytes) && write_all(fd, payload.data(), payload.size());
}

// Address space of this process now (VmSize), 0 when /proc is not there.
std::uint64_t address_space_bytes() {
  std::ifstream statm("/proc/self/statm");
  std::uint64_t pages = 0;
  statm >> pages;
  return pages * static_cast<std::uint64_t>(::sysconf(_SC_PAGESIZE));
}

// Lowers a resource limit (never raises it above the inherited hard limit).
bool lower_limit(int resource, rlim_t soft, rlim_t hard) {
  rlimit old{};
  if (::getrlimit(resource, &old) != 0) return false;
  rlimit lim{soft, hard};
  if (old.rlim_max != RLIM_INFINITY) {
    lim.rlim_max = std::min(lim.rlim_max, old.rlim_max);
    lim.rlim_cur = std::min(lim.rlim_cur, lim.rlim_max);
  }
  return ::setrlimit(resource, &lim) == 0;
}

// An uncaught exception in the child: std::bad_alloc (e.g. from a noexcept function)
// counts as running out of memory; anything else aborts, a crash.
[[noreturn]] void on_terminate() {
  if (const std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
      ::_exit(kExitOutOfMemory);
    } catch (...) {
    }
  }
  std::abort();
}

// The child's whole life; never returns to the caller's code (noexcept: an exception
// escaping the handlers below ends in on_terminate).
[[noreturn]] void child_main(int fd, const std::function<std::string()>& work, const ChildLimits& limits,
                             std::uint64_t inherited_bytes) noexcept {
  std::set_terminate(on_terminate);
  // A crash ends the child; the parent's handlers for these (a test framework's, say)
  // are not for it.
  for (const int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGXCPU}) ::signal(sig, SIG_DFL);
  // The child's stdout is the parent's: whatever the work flushes there (a library's
  // messages, or the copy of the parent's unwritten stdout buffer that fork made) would
  // land in the parent's output (a query's JSON lines). It goes to /dev/null instead.
  if (const int null = ::open("/dev/null", O_WRONLY | O_CLOEXEC); null >= 0) {
    ::dup2(null, STDOUT_FILENO);
    ::close(null);
  }
  char tag = kTagOk;
  std::string reply;
  try {
    const rlim_t as = inherited_bytes + (limits.memory_mib << 20);
    // No core files of a crashed or runaway child; SIGXCPU at the soft CPU limit
    // (default action: terminate), SIGKILL one second later.
    if (lower_limit(RLIMIT_CORE, 0, 0) && lower_limit(RLIMIT_CPU, limits.seconds, limits.seconds + 1) &&
        lower_limit(RLIMIT_AS, as, as)) {
      reply = work();
    } else {
      tag = kTagException;
      reply = errno_text("cannot set the child process's limits");
    }
  } catch (const std::bad_alloc&) {
    ::_exit(kExitOutOfMemory);
  } catch (const Error& e) {
    tag = kTagError;
    reply = e.what();
  } catch (const std::exception& e) {
    tag = kTagException;
    reply = e.what();
  } catch (...) {
    tag = kTagException;
    reply = "unknown exception";
  }
  ::_exit(write_reply(fd, tag, reply) ? 0 : kExitWriteFailed);
}

struct Fd {
  int fd = -1;
  explicit Fd(int f) : fd(f) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { close(); }
  void close() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

// Owns the child: wait() reaps it; if it was not reaped (the parent threw), the
// destructor kills and reaps it, so no path leaves a zombie or a runaway child.
struct ChildProcess {
  pid_t pid;
  bool reaped = false;
  int status = 0;
  rusage usage{};
  explicit ChildProcess(pid_t p) : pid(p) {}
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() {
    if (!reaped) {
      ::kill(pid, SIGKILL);
      wait();
    }
  }
  bool wait() {
    pid_t r;
    do r = ::wait4(pid, &status, 0, &usage);
    while (r < 0 && errno == EINTR);
    reaped = true;
    return r == pid;
  }
  double cpu_seconds() const {
    return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec + 1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
  }
};

// Reads until end of file. False when `deadline` passed first.
bool read_all(int fd, std::chrono::steady_clock::time_point deadline, std::string& out) {
  char buf[1 << 16];
  for (;;) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 1000)));
    if (ready < 0 && errno != EINTR) throw Error(errno_text("cannot wait for the child process"));
    if (ready <= 0) continue;
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (n < 0) throw Error(errno_text("cannot read from the child process"));
    if (n == 0) return true;
    out.append(buf, static_cast<std::size_t>(n));
  }
}

ChildResult reply_result(int exit_status, std::string&& reply) {
  ChildResult r;
  std::uint64_t size = 0;
  if (reply.size() >= kHeaderBytes) std::memcpy(&size, reply.data() + 1, sizeof size);
  const char tag = reply.empty() ? '\0' : reply[0];
  if (exit_status != 0 || reply.size() < kHeaderBytes || size != reply.size() - kHeaderBytes ||
      (tag != kTagOk && tag != kTagError && tag != kTagException)) {
    r.status = ChildResult::Status::bad_reply;
    r.bytes = "exited with status " + std::to_string(exit_status) + " after a malformed reply (" +
              std::to_string(reply.size()) + " bytes)";
    return r;
  }
  r.status = tag == kTagOk      ? ChildResult::Status::ok
             : tag == kTagError ? ChildResult::Status::error
                                : ChildResult::Status::exception;
  reply.erase(0, kHeaderBytes);
  r.bytes = std::move(reply);
  return r;
}

}  // namespace

ChildResult run_in_child(const std::function<std::string()>& work, const ChildLimits& limits) {
  const std::uint64_t inherited = address_space_bytes();
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw Error(errno_text("cannot create a pipe to a child process"));
  Fd read_end(fds[0]), write_end(fds[1]);
  const pid_t pid = ::fork();
  if (pid < 0) throw Error(errno_text("cannot start a child process"));
  if (pid == 0) {
    ::close(fds[0]);
    child_main(fds[1], work, limits, inherited);
  }
  ChildProcess child(pid);
  write_end.close();  // else the read below never sees end of file

  // Drained before waiting: a child blocked on a full pipe would never exit.
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                             std::chrono::duration<double>(limits.wall_seconds));
  std::string reply;
  const bool in_time = read_all(read_end.fd, deadline, reply);
  if (!in_time) ::kill(pid, SIGKILL);
  if (!child.wait()) throw Error(errno_text("cannot wait for the child process"));

  ChildResult r;
  const int st = child.status;
  const bool cpu_limit = child.cpu_seconds() >= limits.seconds;
  if (!in_time || (WIFSIGNALED(st) && (WTERMSIG(st) == SIGXCPU || (WTERMSIG(st) == SIGKILL && cpu_limit)))) {
    r.status = ChildResult::Status::timed_out;
  } else if ((WIFSIGNALED(st) && WTERMSIG(st) == SIGKILL) || (WIFEXITED(st) && WEXITSTATUS(st) == kExitOutOfMemory)) {
    r.status = ChildResult::Status::out_of_memory;  // SIGKILL not sent here: the kernel's OOM killer
  } else if (WIFSIGNALED(st)) {
    r.status = ChildResult::Status::crashed;
    r.signal = WTERMSIG(st);
  } else {
    r = reply_result(WIFEXITED(st) ? WEXITSTATUS(st) : -1, std::move(reply));
  }
  return r;
}

}  // namespace snapfit
