#pragma once
// Scheduling priority for the haptic work (CHAI3D and HAPI run their haptic thread at
// high priority). A query runs on the OpenCL runtime's worker threads (PoCL's pthread
// device), so raising only the loop thread would not help: this raises every thread
// of the process that exists now (the runtime's workers are created with the context).
#include <string>

namespace snapfit {

struct PriorityChange {
  int threads = 0;     // threads whose priority was raised
  int failed = 0;      // threads it could not change (no CAP_SYS_NICE, or gone)
  std::string reason;  // why some failed, for the report
};

// setpriority(2) to `nice_value` (-20 highest .. 19) for every thread of this process.
// Linux only; elsewhere nothing changes and `reason` says so.
PriorityChange raise_process_priority(int nice_value);

}  // namespace snapfit
