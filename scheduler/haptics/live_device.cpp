#include "scheduler/haptics/live_device.h"

#include <algorithm>

namespace snapfit {

LiveDevice::LiveDevice(const BodyState& initial, const DeviceLimits& limits, double late_s, double fade_s)
    : limits_(limits), late_s_(late_s), fade_s_(fade_s), latest_(initial), stamp_(Clock::now()) {}

void LiveDevice::set_state(const BodyState& state, std::uint32_t sequence, Clock::time_point now, bool streamed) {
  const std::lock_guard<std::mutex> lock(mutex_);
  latest_ = state;
  sequence_ = sequence;
  stamp_ = now;
  streamed_ = streamed;
}

void LiveDevice::reset(const BodyState& initial, Clock::time_point now) {
  BodyState at_rest;
  at_rest.pose = initial.pose;
  set_state(at_rest, 0, now, false);
}

float LiveDevice::fade_at(double age_s, double late_s, double fade_s) {
  if (!(age_s > late_s)) return 1;
  if (!(fade_s > 0)) return 0;
  return static_cast<float>(std::clamp(1 - (age_s - late_s) / fade_s, 0.0, 1.0));
}

BodyState LiveDevice::read(double) {
  BodyState state;
  Clock::time_point stamp;
  bool streamed = true;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    state = latest_;
    seen_.sequence = sequence_;
    stamp = stamp_;
    streamed = streamed_;
  }
  age_s_ = streamed ? std::chrono::duration<double>(Clock::now() - stamp).count() : 0;
  seen_.late = age_s_ > late_s_;
  if (seen_.late) {  // held where it was last seen, at rest: no extrapolation of a silent device
    state.velocity.setZero();
    state.angular_velocity.setZero();
  }
  return state;
}

void LiveDevice::send(const Wrench& wrench, double) {
  seen_.fade = fade_at(age_s_, late_s_, fade_s_);
  seen_.sent.force = seen_.fade * wrench.force;
  seen_.sent.torque = seen_.fade * wrench.torque;
  seen_.sanitised = !seen_.sent.force.allFinite() || !seen_.sent.torque.allFinite();
  if (seen_.sanitised) {
    seen_.sent = Wrench{};
    ++sanitised_;
  }
}

}  // namespace snapfit
