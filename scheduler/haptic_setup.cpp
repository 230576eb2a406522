#include "scheduler/haptic_setup.h"

#include <cmath>

#include "engine/error.h"
#include "io/mesh_mass_properties.h"

namespace snapfit {

CouplingParams coupling_for(const Scene& scene, const Mesh& part2_mesh) {
  const HapticsParams& h = scene.haptics;
  const double u = metres_per_unit(scene.units);
  const double r2 = solid_moments(part2_mesh).mean_square_radius * u * u;  // m^2
  const double inertia = (2.0 / 3.0) * h.mass_kg * r2;
  const double rot_stiffness = h.rot_stiffness_nm_per_rad.value_or(h.stiffness_n_per_m * inertia / h.mass_kg);
  return make_coupling(u, h.mass_kg, inertia, h.stiffness_n_per_m, rot_stiffness, h.damping_ratio);
}

DeviceLimits device_limits_for(const Scene& scene) {
  return DeviceLimits{scene.haptics.max_force_n, scene.haptics.max_torque_nm};
}

double geometry_gain_for(const Scene& scene, double spacing, double reference_energy) {
  const HapticsParams& h = scene.haptics;
  if (h.geometry_gain) return *h.geometry_gain;
  if (!(std::isfinite(reference_energy) && reference_energy != 0))
    throw Error("haptics: the energy at the reference pose is " + std::to_string(reference_energy) +
                ", so no geometric gain can be derived from it; set haptics.geometry_gain in the scene");
  const double u = metres_per_unit(scene.units);
  const double force_scale = std::abs(reference_energy) / spacing;  // engine force units
  return h.geometry_strength * h.stiffness_n_per_m * spacing * u / force_scale;
}

Pose gain_reference_pose(const Scene& scene) { return scene.assembled_pose.value_or(scene.part2.pose); }

PoseError pose_error(const Pose& actual, const Pose& target) {
  PoseError e;
  e.position = (actual.translation - target.translation).norm();
  e.angle_deg = rotation_between(actual.rotation, target.rotation).norm() * 180.0 / M_PI;
  return e;
}

}  // namespace snapfit
