#include "core/thread_name.h"

#ifdef __linux__
#include <pthread.h>
#endif

namespace snapfit {

void name_this_thread(const char* name) {
#ifdef __linux__
  char shortened[16] = {};
  for (int i = 0; i < 15 && name[i]; ++i) shortened[i] = name[i];
  pthread_setname_np(pthread_self(), shortened);
#else
  (void)name;
#endif
}

}  // namespace snapfit
