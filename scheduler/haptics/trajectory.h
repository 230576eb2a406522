#pragma once
// The scripted device trajectory of a scene (snapfit/scene.h Trajectory): the pose at any
// time, linear in position and spherical-linear (slerp) in rotation between keyframes,
// held at the first and last keyframe outside their times.
#include <vector>

#include "snapfit/pose.h"
#include "snapfit/scene.h"

namespace snapfit {

// Throws snapfit::Error for an empty trajectory or a non-finite time.
Pose trajectory_pose(const Trajectory& trajectory, double time_s);

// Poses at start + i / rate_hz, i = 0 .. up to the last keyframe's time.
std::vector<Pose> sample_trajectory(const Trajectory& trajectory, double rate_hz);

}  // namespace snapfit
