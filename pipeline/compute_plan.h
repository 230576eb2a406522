#pragma once
// What the engine will compute for a scene, and why: only what the scene needs
// (docs/design.md "Leave out what a scene does not need").
#include <string>
#include <vector>

#include "snapfit/scene.h"

namespace snapfit {

struct ComputePlan {
  bool skeletal_density = true;  // false: winding number (indicator) only
  bool rotation = true;          // spectrum rotation per frame (false: translation fast path)
  bool force = true;
  bool torque = true;
  std::vector<std::string> lines;     // one sentence per decision, with its reason
  std::vector<std::string> warnings;  // settings that will cost accuracy, with what to change
};

// A Voxmap PointShell scene gets that method's own plan (its voxel size, when the scene
// leaves it to the grid, from `grid_spacing` when known, > 0).
ComputePlan plan_computation(const Scene& scene, double grid_spacing = 0);

}  // namespace snapfit
