#include "scheduler/haptics/scripted_device.h"

#include <cmath>

#include "scheduler/haptics/trajectory.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "snapfit/error.h"

namespace snapfit {

ScriptedDevice::ScriptedDevice(Trajectory trajectory, DeviceLimits limits, bool loop_back)
    : trajectory_(std::move(trajectory)), limits_(limits), loop_back_(loop_back) {
  if (trajectory_.keyframes.empty()) throw Error("scripted device: the scene has no trajectory to play");
}

double ScriptedDevice::script_time(double time_s) const {
  const double start = trajectory_.keyframes.front().time_s;
  const double length = trajectory_.keyframes.back().time_s - start;
  if (!loop_back_ || length <= 0 || time_s <= length) return start + time_s;
  // Ping-pong: forwards, backwards, forwards...
  const double phase = std::fmod(time_s, 2.0 * length);
  return start + (phase <= length ? phase : 2.0 * length - phase);
}

BodyState ScriptedDevice::read(double time_s) {
  BodyState s;
  s.pose = trajectory_pose(trajectory_, script_time(time_s));
  const double h = 5e-4;  // central differences over +-0.5 ms of loop time
  const Pose a = trajectory_pose(trajectory_, script_time(std::max(0.0, time_s - h)));
  const Pose b = trajectory_pose(trajectory_, script_time(time_s + h));
  const double span = time_s + h - std::max(0.0, time_s - h);
  s.velocity = (b.translation - a.translation) / span;
  s.angular_velocity = rotation_between(a.rotation, b.rotation) / span;
  return s;
}

void ScriptedDevice::send(const Wrench& wrench, double) {
  last_ = wrench;
  ++sent_;
}

}  // namespace snapfit
