// scheduler/haptics/live_device.h: the live session's device holds a late state at rest, fades the
// wrench linearly from `late` to `late + fade`, and never sends a non-finite wrench.
#include <doctest/doctest.h>
#include <limits>

#include "scheduler/haptics/live_device.h"

using namespace snapfit;

TEST_CASE("live device: the fade is 1 while fresh, linear after late, 0 after late + fade") {
  CHECK(LiveDevice::fade_at(0.004, 0.005, 0.1) == 1.0f);
  CHECK(LiveDevice::fade_at(0.055, 0.005, 0.1) == doctest::Approx(0.5));
  CHECK(LiveDevice::fade_at(0.105, 0.005, 0.1) == doctest::Approx(0.0));
  CHECK(LiveDevice::fade_at(5.0, 0.005, 0.1) == 0.0f);
  CHECK(LiveDevice::fade_at(0.006, 0.005, 0.0) == 0.0f);
}

TEST_CASE("live device: a late state is held at rest and its wrench faded, a NaN wrench goes out as zero") {
  BodyState initial;
  LiveDevice device(initial, DeviceLimits{}, 0.005, 0.1);
  BodyState moving;
  moving.pose.translation = Eigen::Vector3d(1, 2, 3);
  moving.velocity = Eigen::Vector3d(10, 0, 0);
  const auto now = LiveDevice::Clock::now();
  device.set_state(moving, 41, now);
  BodyState read = device.read(0);
  CHECK(read.velocity.x() == 10);
  CHECK(device.seen().sequence == 41);
  CHECK_FALSE(device.seen().late);
  Wrench w;
  w.force = Eigen::Vector3d(2, 0, 0);
  device.send(w, 0);
  CHECK(device.seen().sent.force.x() == 2);

  // 55 ms old: late, held where it was at rest, half the wrench.
  device.set_state(moving, 42, LiveDevice::Clock::now() - std::chrono::milliseconds(55));
  read = device.read(0);
  CHECK(device.seen().late);
  CHECK(read.pose.translation == moving.pose.translation);
  CHECK(read.velocity.norm() == 0);
  device.send(w, 0);
  CHECK(device.seen().fade == doctest::Approx(0.5).epsilon(0.05));
  CHECK(device.seen().sent.force.x() == doctest::Approx(1.0).epsilon(0.05));

  device.set_state(moving, 43, LiveDevice::Clock::now());
  device.read(0);
  Wrench bad;
  bad.torque.y() = std::numeric_limits<double>::quiet_NaN();
  device.send(bad, 0);
  CHECK(device.seen().sanitised);
  CHECK(device.seen().sent.force.norm() == 0);
  CHECK(device.seen().sent.torque.norm() == 0);
  CHECK(device.sanitised_count() == 1);
}
