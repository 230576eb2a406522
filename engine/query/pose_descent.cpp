#include "engine/query/pose_descent.h"

#include <cmath>

#include "snapfit/error.h"

namespace snapfit {

DescentResult descend_pose(QueryEngine& engine, const Pose& start, const DescentOptions& options) {
  DescentResult out;
  out.pose = start;
  QueryResult here = engine.query(start);
  out.queries = 1;
  if (here.flags != query_ok) throw Error("pose descent: the start pose is outside the map grid or not a rotation");
  out.energy = here.energy;
  const double l = options.length;
  double step = options.step;
  while (step >= options.min_step && out.queries < options.max_queries) {
    // Direction in (t, l theta): (F, T / l); its length normalises the step.
    const Eigen::Vector3d dt = here.force, dr = here.torque / l;
    const double norm = std::sqrt(dt.squaredNorm() + dr.squaredNorm());
    if (!(norm > 0)) break;
    Pose trial;
    trial.translation = out.pose.translation + dt * (step / norm);
    const Eigen::Vector3d turn = dr * (step / (norm * l));  // radians about part 2's reference point
    trial.rotation = (Eigen::Quaterniond(Eigen::AngleAxisd(
                          turn.norm(), turn.norm() > 0 ? turn.normalized() : Eigen::Vector3d::UnitX())) *
                      out.pose.rotation)
                         .normalized();
    const QueryResult next = engine.query(trial);
    ++out.queries;
    if (next.flags == query_ok && next.energy < out.energy) {
      out.pose = trial;
      out.energy = next.energy;
      here = next;
      step *= 1.5;
    } else {
      step *= 0.5;
    }
  }
  return out;
}

}  // namespace snapfit
