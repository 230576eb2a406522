#pragma once
// A pose as JSON: the one shape that every file snapfit writes gives a pose in (scene
// files, summary.json, the report's pages, search results), and that scene files read:
//   {"position": [x, y, z], "rotation": {"quaternion": [w, x, y, z]}}
// For any nlohmann JSON type (nlohmann::json, nlohmann::ordered_json); the header itself
// needs none.
#include "snapfit/pose.h"

namespace snapfit {

template <typename Json>
Json pose_json(const Pose& p) {
  const Eigen::Quaterniond& q = p.rotation;
  Json j;
  j["position"] = {p.translation.x(), p.translation.y(), p.translation.z()};
  j["rotation"] = {{"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
  return j;
}

}  // namespace snapfit
