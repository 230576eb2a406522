#pragma once
// A fixed-capacity queue between one producer thread and one consumer thread, without
// locks and without allocation after construction: a real-time thread (the haptic loop)
// hands plain records to a thread that may allocate and block (a recorder). When it is
// full, push() refuses and the producer counts the loss; it never waits.
#include <atomic>
#include <cstddef>
#include <vector>

namespace snapfit {

template <class T>
class SpscRing {
 public:
  // Holds up to `capacity` items (rounded up to a power of two).
  explicit SpscRing(std::size_t capacity) {
    std::size_t n = 1;
    while (n < capacity) n <<= 1;
    slots_.resize(n);
    mask_ = n - 1;
  }

  // Producer only. False when fewer than `keep_free` + 1 slots are free (the item is not
  // queued): a producer that must never lose some items leaves them room.
  bool push(const T& item, std::size_t keep_free = 0) {
    const std::size_t head = head_.load(std::memory_order_relaxed);
    if (head - tail_.load(std::memory_order_acquire) + keep_free > mask_) return false;
    slots_[head & mask_] = item;
    head_.store(head + 1, std::memory_order_release);
    return true;
  }

  // Consumer only. False when empty.
  bool pop(T& item) {
    const std::size_t tail = tail_.load(std::memory_order_relaxed);
    if (tail == head_.load(std::memory_order_acquire)) return false;
    item = slots_[tail & mask_];
    tail_.store(tail + 1, std::memory_order_release);
    return true;
  }

  std::size_t capacity() const { return mask_ + 1; }

 private:
  std::vector<T> slots_;
  std::size_t mask_ = 0;
  alignas(64) std::atomic<std::size_t> head_{0};  // next slot the producer writes
  alignas(64) std::atomic<std::size_t> tail_{0};  // next slot the consumer reads
};

}  // namespace snapfit
