#pragma once
// What the benchmarks that compare with FCL (Debian libfcl-dev) share: a part's BVH model
// and a pose as FCL's transform.
#include <chrono>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#include <memory>
#include <string>
#include <vector>

#include "mesh/mesh.h"
#include "snapfit/error.h"
#include "snapfit/pose.h"

namespace snapfit::bench {

using FclModel = fcl::BVHModel<fcl::OBBRSSd>;

// The mesh as an OBBRSS BVH; `seconds` gets the build time.
inline std::shared_ptr<FclModel> fcl_model(const Mesh& m, double& seconds) {
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<fcl::Vector3d> v(m.vertices.begin(), m.vertices.end());
  std::vector<fcl::Triangle> t;
  t.reserve(m.triangles.size());
  for (const auto& tri : m.triangles) t.emplace_back(std::size_t(tri[0]), std::size_t(tri[1]), std::size_t(tri[2]));
  auto model = std::make_shared<FclModel>();
  if (model->beginModel(int(t.size()), int(v.size())) != fcl::BVH_OK || model->addSubModel(v, t) != fcl::BVH_OK ||
      model->endModel() != fcl::BVH_OK)
    throw Error("FCL: cannot build the BVH model (" + std::to_string(t.size()) + " triangles)");
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return model;
}

inline fcl::Transform3d fcl_transform(const Pose& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear() = p.rotation.toRotationMatrix();
  tf.translation() = p.translation;
  return tf;
}

}  // namespace snapfit::bench
