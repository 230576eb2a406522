// scheduler/haptics/thread_priority.h: raising every thread of the process for the haptic loop
// and putting each back afterwards.
#include <atomic>
#include <cerrno>
#include <chrono>
#include <doctest/doctest.h>
#include <filesystem>
#include <map>
#include <sched.h>
#include <sys/resource.h>
#include <thread>

#include "scheduler/haptics/thread_priority.h"

namespace snapfit {
namespace {

struct ThreadPolicy {
  int policy = -1, priority = -1, nice = 0;
  bool operator==(const ThreadPolicy& o) const {
    return policy == o.policy && priority == o.priority && nice == o.nice;
  }
};

std::map<int, ThreadPolicy> thread_policies() {
  std::map<int, ThreadPolicy> out;
  for (const auto& entry : std::filesystem::directory_iterator("/proc/self/task")) {
    const int tid = std::atoi(entry.path().filename().c_str());
    ThreadPolicy p;
    p.policy = sched_getscheduler(tid);
    sched_param param{};
    sched_getparam(tid, &param);
    p.priority = param.sched_priority;
    errno = 0;
    p.nice = getpriority(PRIO_PROCESS, static_cast<id_t>(tid));
    out[tid] = p;
  }
  return out;
}

}  // namespace

TEST_CASE("thread priority: every thread is raised (SCHED_FIFO where allowed, else nice) and restored") {
  // A second thread, as the OpenCL runtime's workers are.
  std::atomic<bool> stop{false};
  std::thread worker([&] {
    while (!stop) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  });
  const std::map<int, ThreadPolicy> before = thread_policies();
  REQUIRE(before.size() >= 2);

  PriorityRequest request;
  request.nice_value = -5;
  request.realtime_priority = 3;
  const PriorityChange change = raise_process_priority(request);
  const std::map<int, ThreadPolicy> during = thread_policies();
  MESSAGE("raised: " << change.describe());
  CHECK(change.threads + change.failed == static_cast<int>(before.size()));
  CHECK(change.previous.size() == static_cast<std::size_t>(change.threads));
  int fifo = 0, niced = 0;
  for (const auto& [tid, p] : during) {
    if (p.policy == SCHED_FIFO && p.priority == 3)
      ++fifo;
    else if (p.nice == -5)
      ++niced;
  }
  CHECK(fifo == change.realtime);
  CHECK(niced == change.threads - change.realtime);
  if (change.failed > 0) CHECK(!change.reason.empty());

  restore_process_priority(change);
  CHECK(thread_policies() == before);
  stop = true;
  worker.join();

  // Nothing asked, nothing changed.
  const PriorityChange none = raise_process_priority(PriorityRequest{0, 0});
  CHECK(none.threads == 0);
  CHECK(none.describe() == "unchanged");
}

}  // namespace snapfit
