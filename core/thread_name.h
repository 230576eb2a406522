#pragma once
// Names the calling thread (Linux: at most 15 characters, as top, ps -L and perf show
// it), so the haptic loop and its background workers can be told apart when timing them.

namespace snapfit {

void name_this_thread(const char* name);

}  // namespace snapfit
