#pragma once
// A haptic device that plays a scene's scripted trajectory (scheduler/haptics/trajectory.h):
// unattended runs, tests and benchmarks. Velocities are central differences of the
// trajectory. The wrenches it is sent are kept for the report.
#include <vector>

#include "snapfit/haptic_device.h"
#include "snapfit/scene.h"

namespace snapfit {

class ScriptedDevice : public HapticDevice {
 public:
  // `loop_back`: after the last keyframe, play the trajectory backwards and forwards
  // again (for long benchmark runs); otherwise hold the last keyframe.
  ScriptedDevice(Trajectory trajectory, DeviceLimits limits, bool loop_back = false);

  BodyState read(double time_s) override;
  void send(const Wrench& wrench, double time_s) override;
  DeviceLimits limits() const override { return limits_; }

  // The trajectory time the device plays at loop time `time_s`.
  double script_time(double time_s) const;
  const Wrench& last_sent() const { return last_; }
  std::size_t sent_count() const { return sent_; }

 private:
  Trajectory trajectory_;
  DeviceLimits limits_;
  bool loop_back_;
  Wrench last_;
  std::size_t sent_ = 0;
};

}  // namespace snapfit
