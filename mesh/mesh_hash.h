#pragma once
// A hash of a mesh's content (vertex positions and triangle indices, as stored), for
// cache keys: any change to the mesh gives another key.
#include <cstdint>

#include "core/hash.h"
#include "mesh/mesh.h"

namespace snapfit {

inline std::uint64_t mesh_hash(const Mesh& mesh) {
  const std::uint64_t h = fnv1a64(mesh.vertices.data(), mesh.vertices.size() * sizeof(Eigen::Vector3d));
  return fnv1a64(mesh.triangles.data(), mesh.triangles.size() * sizeof(Eigen::Vector3i), h);
}

}  // namespace snapfit
