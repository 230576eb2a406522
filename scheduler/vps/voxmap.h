#pragma once
// Voxmap PointShell geometry (McNeely, Puterbaugh & Troy 1999; seed 002 section 4.1):
// the fixed part as a voxmap, a regular grid of voxels classified free / surface /
// interior / proximity, with distance layers (how many voxels an interior voxel lies
// inside the surface layer, how many a proximity voxel lies outside it); the moving part
// as a point shell, points on its surface at voxel density, each with its inward normal.
#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <vector>

#include "mesh/mesh.h"
#include "mesh/shell_chunk.h"

namespace snapfit {

enum class VoxelState : std::uint8_t { free, surface, interior, proximity };

struct Voxmap {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // centre of voxel (0, 0, 0)
  double voxel_size = 0;
  Eigen::Vector3i dims = Eigen::Vector3i::Zero();
  int proximity_layers = 0;
  std::vector<VoxelState> state;  // x fastest
  // Layers from the surface (26-neighbourhood steps): 0 on the surface; interior and
  // free voxels count up to 255 (free ones beyond proximity_layers are plain free space,
  // their layer a lower bound on their distance, for culling).
  std::vector<std::uint8_t> layer;

  std::size_t index(int i, int j, int k) const {
    return static_cast<std::size_t>(i) +
           static_cast<std::size_t>(dims.x()) * (j + static_cast<std::size_t>(dims.y()) * k);
  }
  Eigen::Vector3d centre(int i, int j, int k) const { return origin + voxel_size * Eigen::Vector3d(i, j, k); }
  // The voxel holding p, or false outside the map.
  bool locate(const Eigen::Vector3d& p, Eigen::Vector3i& ijk) const {
    const Eigen::Vector3d g = (p - origin) / voxel_size;
    for (int a = 0; a < 3; ++a) {
      const double r = std::floor(g[a] + 0.5);
      if (!(r >= 0 && r < dims[a])) return false;
      ijk[a] = static_cast<int>(r);
    }
    return true;
  }
  std::size_t count(VoxelState s) const;
};

// Voxelises a closed, outward-oriented mesh: surface voxels are those a triangle
// overlaps (exact triangle-box test), interior voxels the others whose centre is inside
// (winding count along +z), proximity voxels the free ones within `proximity_layers`
// (26-neighbourhood) of the surface. The map covers the mesh's box plus the proximity
// layers and one free voxel. Throws snapfit::Error for an empty mesh or a bad size.
Voxmap build_voxmap(const Mesh& mesh, double voxel_size, int proximity_layers);

struct PointShell {
  std::vector<Eigen::Vector3d> points;   // in the part's frame, grouped by chunk
  std::vector<Eigen::Vector3d> normals;  // unit, inward
  std::vector<ShellChunk> chunks;
  double spacing = 0;
  double radius = 0;  // largest |point|: how far a point lies from the part's origin
};

// One point per surface voxel of the part at `spacing`: the point of the surface closest
// to the voxel's centre, with the inward normal of its triangle; points grouped into
// chunks of 8 x 8 x 8 voxels. Throws snapfit::Error for an empty mesh or a bad spacing.
PointShell build_point_shell(const Mesh& mesh, double spacing);

}  // namespace snapfit
