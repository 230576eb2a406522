#pragma once
// Heap allocations made by the calling thread while a CountAllocations lives, as counted
// by the test binary's replaced global operator new (tests/test_query_engine.cpp). Other
// threads (an OpenCL runtime's workers) are not counted.
#include <atomic>

namespace snapfit::test {

extern thread_local bool counting_allocations;
extern std::atomic<long> allocations;

struct CountAllocations {
  long before = allocations.load();
  CountAllocations() { counting_allocations = true; }
  ~CountAllocations() { counting_allocations = false; }
  long count() const { return allocations.load() - before; }
};

}  // namespace snapfit::test
