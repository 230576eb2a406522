#pragma once
// Voxmap PointShell (McNeely, Puterbaugh & Troy 1999; seed 002 section 4.1) as a peer
// of snapfit's engine in the same haptic loop: part 1 as a voxmap, part 2 as a point
// shell (scheduler/vps/voxmap.h). Each frame, every shell point (at part 2's pose, in part 1's
// frame) that lies in a surface or interior voxel pushes part 2 along its inward normal
// n with the tangent-plane force model (seed 002 Fig. 13B, eq. 3):
//     d = max(0, (c - p).n + l s),   F_i = k_ff d n,   tau_i = (p - t) x F_i
// with c the voxel's centre, s the voxel size and l the voxel's interior layer (0 in the
// surface layer); forces and torques sum about part 2's origin t. Points in proximity
// voxels that approach part 1 (v_p.n < 0) get the pre-contact braking force
// F_i = -b_ff (v_p.n) n (seed 002 eq. 5), scaled down as a whole so that it never removes
// more than half the approach velocity in one step (it is held over the step, explicitly).
// The speed limit (no point travels more than half a voxel per frame) is the loop's
// LoopConfig::max_travel.
#include <memory>

#include "scheduler/vps/voxmap.h"
#include "snapfit/haptic_device.h"
#include "snapfit/haptic_loop.h"
#include "snapfit/query.h"
#include "snapfit/scene.h"

namespace snapfit {

struct VpsModel {
  Voxmap voxmap;         // part 1
  PointShell shell;      // part 2, in its own frame
  double stiffness = 0;  // k_ff per point, N / m
  double braking = 0;    // b_ff per point, N s / m
  double metres_per_unit = 1e-3;
  double mass_kg = 0.05;  // part 2's simulated mass and inertia: bound the braking
  double inertia_kg_m2 = 1e-5;
  double period_s = 1e-3;
};

// The contact wrench on part 2 in state `part` (pose relative to part 1, velocities in
// part 1's frame), as the loop reads a query: force in N, torque in N per scene unit of
// lever arm (the loop multiplies it by metres_per_unit), energy sum 1/2 k_ff d^2 in J
// per metre_per_unit. `contacts` and `braking_points` count the points that acted.
struct VpsResult {
  QueryResult query;
  std::size_t contacts = 0;
  std::size_t braking_points = 0;
  double max_depth = 0;  // scene units, the deepest point's d
};
// `sink`, when given, receives each contact point's force and torque (as summed into
// the query) with its voxel's and shell point's indices: what the hybrid method blends.
struct VpsContactSink {
  void* context = nullptr;
  void (*contact)(void* context, std::size_t voxel, std::size_t point, const Eigen::Vector3d& force,
                  const Eigen::Vector3d& torque) = nullptr;
};
VpsResult vps_wrench(const VpsModel& model, const BodyState& part, const VpsContactSink* sink = nullptr);

// The model of a scene: voxel size (default `spacing`), k_ff and shell density from its
// `vps` section, mass and inertia from the coupling. Throws snapfit::Error for bad input.
VpsModel vps_model_for(const Scene& scene, const Mesh& part1, const Mesh& part2, double spacing,
                       const CouplingParams& coupling);

// The loop's view of the model; it may not outlive `model`.
WrenchEvaluator vps_evaluator(const VpsModel& model);

// The loop configuration of a VPS run: rate, budget, duration and coupling as for
// snapfit, geometry gain 1 (forces are already in N), one "m'" level, and the speed
// limit of half a voxel per frame for the farthest shell point.
LoopConfig vps_loop_config(const Scene& scene, const VpsModel& model, const CouplingParams& coupling);

}  // namespace snapfit
