#pragma once
// What the haptic loop needs from a device (CHAI3D / HAPI style): read the handle's
// pose and velocity, send a force and torque, and know the device's limits. A real
// device (CHAI3D's cGenericHapticDevice, OpenHaptics' HD API) plugs in by implementing
// this interface; snapfit's own scripted device plays a scene's trajectory instead.
// Poses are part 2's device pose relative to part 1, in scene units; velocities in
// part 1's frame.
#include <Eigen/Core>
#include <limits>

#include "snapfit/pose.h"

namespace snapfit {

// Force and torque on part 2 (or, sent to the device, on the user's hand).
struct Wrench {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();   // N
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();  // N m, about part 2's reference point
};

// A rigid body's state: pose (scene units) and velocities in part 1's frame.
struct BodyState {
  Pose pose;
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // scene units / s
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // rad / s
};

struct DeviceLimits {
  double max_force_n = std::numeric_limits<double>::infinity();
  double max_torque_nm = std::numeric_limits<double>::infinity();  // 0 for 3-DOF-output devices
};

class HapticDevice {
 public:
  virtual ~HapticDevice() = default;
  // The handle's pose and velocities at loop time `time_s` (seconds since the loop began).
  virtual BodyState read(double time_s) = 0;
  // The wrench to render from now on (already clamped to limits()).
  virtual void send(const Wrench& wrench, double time_s) = 0;
  virtual DeviceLimits limits() const = 0;
};

// Scales force and torque down (keeping their directions) to the device's limits.
// A non-finite wrench becomes zero: a NaN must never reach a person's hand.
Wrench clamp_to_limits(const Wrench& wrench, const DeviceLimits& limits);

}  // namespace snapfit
