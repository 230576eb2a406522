#pragma once
// Background workers (the exact-rotation product, the near part) take only what the
// haptic frame leaves of the CPU. On PoCL's single-threaded driver a kernel runs on the
// thread that enqueues it, so the worker's own priority is the kernel's.

namespace snapfit {

// Puts the calling thread in SCHED_IDLE (Linux; elsewhere nothing). Cheap when it is
// there already, so a worker calls it each round, in case a priority change since
// made it an ordinary thread again.
void yield_to_the_frame();

// Whether a thread (a Linux thread id; 0: the caller) is in SCHED_IDLE: a background
// worker, which a priority raise for the haptic loop leaves alone.
bool is_background_thread(int tid = 0);

}  // namespace snapfit
