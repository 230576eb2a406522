#include "scheduler/haptics/thread_priority.h"

#include <cerrno>
#include <cstring>
#include <filesystem>

#include "core/background_priority.h"

#ifdef __linux__
#include <sched.h>
#include <sys/resource.h>
#endif

namespace snapfit {

std::string ThreadPriority::describe() const {
  std::string s;
  if (realtime > 0)
    s = "SCHED_FIFO " + std::to_string(realtime_priority) + " for " + std::to_string(realtime) + " threads";
  if (threads > realtime) {
    if (!s.empty()) s += ", ";
    s += "nice " + std::to_string(nice_value) + " for " + std::to_string(threads - realtime) + " threads";
  }
  if (s.empty()) s = "unchanged";
  if (failed > 0) s += "; failed for " + std::to_string(failed) + " (" + reason + ")";
  return s;
}

PriorityChange raise_process_priority(const PriorityRequest& request) {
  PriorityChange change;
  change.realtime_priority = request.realtime_priority;
  change.nice_value = request.nice_value;
#ifdef __linux__
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task", ec)) {
    const int tid = std::atoi(entry.path().filename().c_str());
    if (tid <= 0 || is_background_thread(tid)) continue;  // a worker that yields to the frame
    PriorityChange::Previous before;
    before.tid = tid;
    before.policy = sched_getscheduler(tid);
    sched_param param{};
    sched_getparam(tid, &param);
    before.priority = param.sched_priority;
    errno = 0;
    before.nice = getpriority(PRIO_PROCESS, static_cast<id_t>(tid));
    if (before.policy < 0 || errno != 0) {
      ++change.failed;
      change.reason = std::strerror(errno ? errno : ESRCH);
      continue;
    }
    if (request.realtime_priority > 0) {
      sched_param rt{};
      rt.sched_priority = request.realtime_priority;
      if (sched_setscheduler(tid, SCHED_FIFO, &rt) == 0) {
        ++change.threads;
        ++change.realtime;
        change.previous.push_back(before);
        continue;
      }
      change.reason = std::string("SCHED_FIFO: ") + std::strerror(errno);
    }
    // On Linux, PRIO_PROCESS with a thread id sets that thread's nice value.
    if (request.nice_value != 0 && setpriority(PRIO_PROCESS, static_cast<id_t>(tid), request.nice_value) == 0) {
      ++change.threads;
      change.previous.push_back(before);
    } else if (request.nice_value != 0) {
      ++change.failed;
      change.reason = std::strerror(errno);
    }
  }
  if (ec) change.reason = "cannot list /proc/self/task: " + ec.message();
#else
  (void)request;
  change.reason = "thread priorities are only raised on Linux";
#endif
  return change;
}

void restore_process_priority(const PriorityChange& change) {
#ifdef __linux__
  for (const PriorityChange::Previous& p : change.previous) {
    sched_param param{};
    param.sched_priority = p.priority;
    sched_setscheduler(p.tid, p.policy, &param);
    setpriority(PRIO_PROCESS, static_cast<id_t>(p.tid), p.nice);
  }
#else
  (void)change;
#endif
}

}  // namespace snapfit
