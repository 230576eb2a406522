#pragma once
// Scheduling priority for the haptic work (CHAI3D and HAPI run their haptic thread at
// high priority). A query runs on the OpenCL runtime's worker threads (PoCL's pthread
// device), so raising only the loop thread would not help: this raises every thread
// of the process that exists now (the runtime's workers are created with the context).
#include <string>
#include <vector>

#include "snapfit/job_facts.h"  // ThreadPriority

namespace snapfit {

struct PriorityRequest {
  int nice_value = -10;  // setpriority(2), -20 highest .. 19; 0 leaves the nice value
  // SCHED_FIFO priority (1-99) tried first, above every normally scheduled task (the
  // kernel's real-time throttling still leaves 5% of each second to them); 0: nice only.
  int realtime_priority = 0;
};

// What was done (ThreadPriority, include/snapfit/job_facts.h), and what each changed thread
// had before, for restore_process_priority.
struct PriorityChange : ThreadPriority {
  struct Previous {
    int tid = 0, policy = 0, priority = 0, nice = 0;
  };
  std::vector<Previous> previous;
};

// Raises every thread of this process but the background workers (SCHED_IDLE,
// core/background_priority.h), which stay below the frame: SCHED_FIFO at
// request.realtime_priority when asked and allowed (CAP_SYS_NICE), else the nice value. Linux only; elsewhere nothing
// changes and `reason` says so.
PriorityChange raise_process_priority(const PriorityRequest& request);

// Puts back the policy and nice value each changed thread had (threads gone since are
// skipped).
void restore_process_priority(const PriorityChange& change);

}  // namespace snapfit
