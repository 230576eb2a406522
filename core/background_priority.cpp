#include "core/background_priority.h"

#ifdef __linux__
#include <sched.h>
#endif

namespace snapfit {

void yield_to_the_frame() {
#ifdef __linux__
  if (sched_getscheduler(0) != SCHED_IDLE) {
    sched_param none{};
    none.sched_priority = 0;
    sched_setscheduler(0, SCHED_IDLE, &none);
  }
#endif
}

bool is_background_thread(int tid) {
#ifdef __linux__
  return sched_getscheduler(tid) == SCHED_IDLE;
#else
  (void)tid;
  return false;
#endif
}

}  // namespace snapfit
