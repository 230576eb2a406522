#include "scheduler/vps/vps_method.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "scheduler/haptics/haptic_setup.h"
#include "snapfit/error.h"

namespace snapfit {

VpsResult vps_wrench(const VpsModel& model, const BodyState& part, const VpsContactSink* sink) {
  const auto start = std::chrono::steady_clock::now();
  const Voxmap& map = model.voxmap;
  const PointShell& shell = model.shell;
  const double u = model.metres_per_unit;
  const Eigen::Matrix3d rotation = part.pose.rotation.toRotationMatrix();
  const Eigen::Vector3d& origin = part.pose.translation;
  VpsResult out;
  QueryResult& q = out.query;
  Eigen::Vector3d brake_force = Eigen::Vector3d::Zero(), brake_torque = Eigen::Vector3d::Zero();
  double brake_lever2 = 0;  // sum of |r|^2 over braking points: their rotational damping
  Eigen::Vector3i ijk;
  const Eigen::Vector3d map_lo = map.origin - 0.5 * map.voxel_size * Eigen::Vector3d::Ones();
  const Eigen::Vector3d map_hi = map_lo + map.voxel_size * map.dims.cast<double>();
  for (const ShellChunk& chunk : shell.chunks) {
    // Hierarchical culling (McNeely 1999): a chunk whose centre lies outside the map, or
    // in free space, farther from it or from part 1's surface layer than its radius plus
    // the proximity layers, holds no point in a proximity, surface or interior voxel.
    const Eigen::Vector3d centre = origin + rotation * chunk.centre;
    const double outside = (map_lo - centre).cwiseMax(centre - map_hi).cwiseMax(0.0).norm();
    if (outside > chunk.radius) continue;
    if (map.locate(centre, ijk)) {
      const std::size_t id = map.index(ijk.x(), ijk.y(), ijk.z());
      const double clear = (map.layer[id] - map.proximity_layers - 2) * map.voxel_size;
      if (map.state[id] == VoxelState::free && clear > chunk.radius) continue;
    }
    for (std::size_t i = chunk.begin; i < chunk.end; ++i) {
      const Eigen::Vector3d r = rotation * shell.points[i];  // lever arm about part 2's origin
      const Eigen::Vector3d p = origin + r;
      if (!map.locate(p, ijk)) continue;
      const std::size_t id = map.index(ijk.x(), ijk.y(), ijk.z());
      const VoxelState state = map.state[id];
      if (state == VoxelState::free) continue;
      const Eigen::Vector3d n = rotation * shell.normals[i];
      if (state == VoxelState::proximity) {
        // Pre-contact braking of a point approaching part 1 (seed 002 eq. 5).
        const double approach = (part.velocity + part.angular_velocity.cross(r)).dot(n);
        if (approach < 0 && model.braking > 0) {
          const Eigen::Vector3d f = -model.braking * u * approach * n;
          brake_force += f;
          brake_torque += r.cross(f);
          brake_lever2 += r.squaredNorm();
          ++out.braking_points;
        }
        continue;
      }
      // Tangent plane through the voxel's centre, normal to the point's normal (seed 002
      // Fig. 13B); interior voxels add their depth below the surface layer.
      const double interior = state == VoxelState::interior ? map.layer[id] * map.voxel_size : 0.0;
      const double depth = std::max(0.0, (map.centre(ijk.x(), ijk.y(), ijk.z()) - p).dot(n) + interior);
      if (depth <= 0) continue;
      const Eigen::Vector3d f = model.stiffness * u * depth * n;  // eq. 3, N
      const Eigen::Vector3d torque = r.cross(f);                  // N per scene unit of lever arm
      q.force += f;
      q.torque += torque;
      if (sink) sink->contact(sink->context, id, i, f, torque);
      q.energy += 0.5 * model.stiffness * u * depth * depth;  // J / metres_per_unit
      out.max_depth = std::max(out.max_depth, depth);
      ++out.contacts;
    }
  }
  if (out.braking_points > 0) {
    // The braking force is held over the step (explicit): keep its total damping below
    // half of what would stop the part in one step, in translation and in rotation.
    const double b_total = model.braking * out.braking_points;
    const double b_rot_total = model.braking * u * u * brake_lever2;
    double scale = 1;
    if (b_total * model.period_s > 0.5 * model.mass_kg) scale = 0.5 * model.mass_kg / (b_total * model.period_s);
    if (b_rot_total * model.period_s > 0.5 * model.inertia_kg_m2)
      scale = std::min(scale, 0.5 * model.inertia_kg_m2 / (b_rot_total * model.period_s));
    q.force += scale * brake_force;
    q.torque += scale * brake_torque;
  }
  q.modes = 1;
  q.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

VpsModel vps_model_for(const Scene& scene, const Mesh& part1, const Mesh& part2, double spacing,
                       const CouplingParams& coupling) {
  const VpsParams& p = scene.vps;
  VpsModel m;
  const double voxel = p.voxel_size.value_or(spacing);
  if (!(std::isfinite(voxel) && voxel > 0))
    throw Error("vps: the voxel size must be > 0 (got " + std::to_string(voxel) + ")");
  m.voxmap = build_voxmap(part1, voxel, p.proximity_layers);
  m.shell = build_point_shell(part2, voxel / p.shell_density);
  m.stiffness = p.stiffness_n_per_m;
  m.mass_kg = coupling.mass_kg;
  m.inertia_kg_m2 = coupling.inertia_kg_m2;
  m.braking = p.braking_n_s_per_m.value_or(0.1 * 2.0 * std::sqrt(p.stiffness_n_per_m * coupling.mass_kg));
  m.metres_per_unit = coupling.metres_per_unit;
  m.period_s = 1.0 / scene.loop_rate_hz;
  return m;
}

WrenchEvaluator vps_evaluator(const VpsModel& model) {
  WrenchEvaluator e;
  e.evaluate = [&model](const Pose& pose) {
    BodyState s;
    s.pose = pose;
    return vps_wrench(model, s).query;
  };
  e.evaluate_state = [&model](const BodyState& s) { return vps_wrench(model, s).query; };
  e.set_modes = [](std::size_t) {};
  return e;
}

LoopConfig vps_loop_config(const Scene& scene, const VpsModel& model, const CouplingParams& coupling) {
  LoopConfig config = scene_loop_config(scene, coupling);
  config.geometry_gain = 1;
  config.modes.levels = {1};
  // Speed limit (McNeely 1999): no shell point moves more than half a voxel per frame.
  config.max_travel = 0.5 * model.voxmap.voxel_size;
  config.max_rotation = model.shell.radius > 0 ? config.max_travel / model.shell.radius : 0.0;
  config.max_force_rate_n_per_s = 0;  // the peer as published: no bound on the force's rate
  return config;
}

}  // namespace snapfit
