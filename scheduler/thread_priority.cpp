#include "scheduler/thread_priority.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#ifdef __linux__
#include <sys/resource.h>
#endif

namespace snapfit {

PriorityChange raise_process_priority(int nice_value) {
  PriorityChange change;
#ifdef __linux__
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    const int tid = std::atoi(entry.path().filename().c_str());
    if (tid <= 0) continue;
    // On Linux, PRIO_PROCESS with a thread id sets that thread's nice value.
    if (setpriority(PRIO_PROCESS, static_cast<id_t>(tid), nice_value) == 0) {
      ++change.threads;
    } else {
      ++change.failed;
      change.reason = std::strerror(errno);
    }
  }
  if (ec) change.reason = "cannot list /proc/self/task: " + ec.message();
#else
  (void)nice_value;
  change.reason = "thread priorities are only raised on Linux";
#endif
  return change;
}

}  // namespace snapfit
