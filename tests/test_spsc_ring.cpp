// core/spsc_ring.h: a full queue refuses (leaving the slots asked for), and a million
// items cross from one thread to another complete and in order.
#include <doctest/doctest.h>

#include <thread>

#include "core/spsc_ring.h"

using namespace snapfit;

TEST_CASE("spsc ring: full refuses, keep_free leaves room, order kept across threads") {
  SpscRing<int> ring(5);
  CHECK(ring.capacity() == 8);
  int out = 0;
  CHECK(!ring.pop(out));
  for (int i = 0; i < 6; ++i) CHECK(ring.push(i, 2));
  CHECK(!ring.push(6, 2));  // two slots left, kept
  CHECK(ring.push(6));
  CHECK(ring.push(7));
  CHECK(!ring.push(8));  // full
  for (int i = 0; i < 8; ++i) {
    REQUIRE(ring.pop(out));
    CHECK(out == i);
  }
  CHECK(!ring.pop(out));

  constexpr int kItems = 1000000;
  SpscRing<int> queue(1024);
  std::thread producer([&] {
    for (int i = 0; i < kItems;)
      if (queue.push(i)) ++i;
  });
  int expected = 0;
  bool in_order = true;
  while (expected < kItems)
    if (queue.pop(out)) in_order = in_order && out == expected++;
  producer.join();
  CHECK(in_order);
  CHECK(!queue.pop(out));
}
