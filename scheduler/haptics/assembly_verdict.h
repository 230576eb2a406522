#pragma once
// Whether part 2 is assembled: its pose within the position and angle tolerances of the
// assembled pose, or its surface within the position tolerance of where the assembled
// pose puts it (the two-sided Hausdorff distance between the two placements,
// mesh/surface_deviation.h). The second counts a pose that the part's symmetry makes
// equal to the assembled one: a round peg turned about its own axis is assembled, though
// its pose is 90 degrees off. `snapfit run`'s verdict and the live session's use it.
#include "mesh/mesh.h"
#include "mesh/surface_deviation.h"
#include "scheduler/haptics/haptic_setup.h"
#include "snapfit/pose.h"

namespace snapfit {

struct AssemblyVerdict {
  PoseError pose;            // against the assembled pose
  SurfaceDeviation surface;  // part 2's surface at the pose against at the assembled pose
  bool assembled = false;    // pose within both tolerances, or surface within the position one
};

class AssemblyJudge {
 public:
  // Part 2's surface is sampled about position_tolerance / 2 apart. Throws
  // snapfit::Error for an empty mesh or a position tolerance that is not positive.
  AssemblyJudge(const Mesh& part2_mesh, const Pose& assembled, double position_tolerance, double angle_tolerance_deg);

  AssemblyVerdict judge(const Pose& part2_pose) const;
  // The same rule for a pose error and a surface deviation measured already.
  bool assembled(const PoseError& pose, double surface_deviation) const;
  // Only the surface's half of the rule's measurements (the costly part).
  SurfaceDeviation surface(const Pose& part2_pose) const { return meter_.between(part2_pose, assembled_); }

 private:
  SurfaceDeviationMeter meter_;
  Pose assembled_;
  double position_tolerance_, angle_tolerance_deg_;
};

}  // namespace snapfit
