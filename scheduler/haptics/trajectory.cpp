#include "scheduler/haptics/trajectory.h"

#include <algorithm>
#include <cmath>

#include "snapfit/error.h"

namespace snapfit {

Pose trajectory_pose(const Trajectory& trajectory, double time_s) {
  const std::vector<Keyframe>& keys = trajectory.keyframes;
  if (keys.empty()) throw Error("the scene has no trajectory keyframes");
  if (!std::isfinite(time_s)) throw Error("trajectory time must be finite");
  if (time_s <= keys.front().time_s) return keys.front().pose;
  if (time_s >= keys.back().time_s) return keys.back().pose;
  const auto next =
      std::upper_bound(keys.begin(), keys.end(), time_s, [](double t, const Keyframe& k) { return t < k.time_s; });
  const Keyframe& b = *next;
  const Keyframe& a = *(next - 1);
  const double s = (time_s - a.time_s) / (b.time_s - a.time_s);
  Pose pose;
  pose.translation = (1.0 - s) * a.pose.translation + s * b.pose.translation;
  pose.rotation = a.pose.rotation.slerp(s, b.pose.rotation).normalized();
  return pose;
}

std::vector<Pose> sample_trajectory(const Trajectory& trajectory, double rate_hz) {
  if (trajectory.keyframes.empty()) throw Error("the scene has no trajectory keyframes");
  if (!(rate_hz > 0) || !std::isfinite(rate_hz)) throw Error("trajectory sampling rate must be a positive number");
  const double start = trajectory.keyframes.front().time_s, end = trajectory.keyframes.back().time_s;
  std::vector<Pose> poses;
  for (long i = 0;; ++i) {
    const double t = start + i / rate_hz;
    if (t > end + 1e-12) break;
    poses.push_back(trajectory_pose(trajectory, t));
  }
  return poses;
}

}  // namespace snapfit
