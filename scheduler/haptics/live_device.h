#pragma once
// The haptic device of a live session: whatever sets its state from another thread (a
// browser's mouse, a device program through the bridge) is what the loop reads. A state
// older than `late` is held at rest, and the wrench sent back fades linearly to zero
// over `fade` after it; a wrench that is not finite is sent as zero and counted.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>

#include "snapfit/haptic_device.h"

namespace snapfit {

class LiveDevice final : public HapticDevice {
 public:
  using Clock = std::chrono::steady_clock;
  LiveDevice(const BodyState& initial, const DeviceLimits& limits, double late_s, double fade_s);

  // Any thread: the device's state now, with the sender's sequence number. A streamed
  // state (a device program's, every frame) goes late when the next does not follow; a
  // held one (a mouse's pose) stays valid until the next.
  void set_state(const BodyState& state, std::uint32_t sequence, Clock::time_point now = Clock::now(),
                 bool streamed = true);
  // Any thread: the state `initial` as if just sent (a reset).
  void reset(const BodyState& initial, Clock::time_point now = Clock::now());

  // The loop's thread.
  BodyState read(double time_s) override;
  void send(const Wrench& wrench, double time_s) override;
  DeviceLimits limits() const override { return limits_; }

  // What the last read and send of the loop's thread saw (read them on that thread).
  struct Seen {
    std::uint32_t sequence = 0;
    bool late = false;
    float fade = 1;      // the factor the last wrench was sent with
    Wrench sent;         // after the fade
    bool sanitised = false;
  };
  const Seen& seen() const { return seen_; }
  std::size_t sanitised_count() const { return sanitised_; }
  // The fade factor at `age_s` seconds since the last state.
  static float fade_at(double age_s, double late_s, double fade_s);

 private:
  DeviceLimits limits_;
  double late_s_, fade_s_;
  mutable std::mutex mutex_;  // guards the four below
  BodyState latest_;
  std::uint32_t sequence_ = 0;
  Clock::time_point stamp_;
  bool streamed_ = true;
  Seen seen_;
  double age_s_ = 0;  // of the state the last read returned
  std::atomic<std::size_t> sanitised_{0};  // read from other threads
};

}  // namespace snapfit
