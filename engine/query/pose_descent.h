#pragma once
// Local 6-DOF refinement of a pose by descent on the query engine's energy: steps along
// (F, T / l^2) (F = -dE/dt, T = -dE/dtheta, include/snapfit/query.h), i.e. steepest
// descent in the coordinates (t, l theta) with l a length of part 2, so one step length
// in scene units moves points of part 2 about that far whether it translates or turns.
// A step that lowers E is taken and the next one is 1.5x longer; one that does not is
// halved; the descent stops when the step is below `min_step` or after `max_queries`.
#include <cstddef>

#include "snapfit/pose.h"
#include "snapfit/query.h"

namespace snapfit {

struct DescentOptions {
  double length = 1;  // l: part 2's radius, scene units
  double step = 1;    // first step length, scene units
  double min_step = 0.01;
  std::size_t max_queries = 200;
};

struct DescentResult {
  Pose pose;
  double energy = 0;
  std::size_t queries = 0;
};

// Throws snapfit::Error when the start pose gives a flagged query (outside the grid or
// not a rotation). Poses that would alias are refused as steps.
DescentResult descend_pose(QueryEngine& engine, const Pose& start, const DescentOptions& options);

}  // namespace snapfit
