#pragma once
// Validation report of a triangle mesh: what `snapfit mesh-info` prints.
#include <Eigen/Core>
#include <cstddef>
#include <string>

#include "mesh/mesh.h"

namespace snapfit {

struct MeshReport {
  std::size_t vertex_count = 0;  // distinct vertex positions (after welding)
  std::size_t triangle_count = 0;
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
  std::size_t degenerate_triangles = 0;  // repeated vertex or (near-)zero area
  std::size_t boundary_edges = 0;        // edges with one incident triangle (open mesh)
  std::size_t non_manifold_edges = 0;    // edges with more than two incident triangles
  std::size_t inconsistent_edges = 0;    // two triangles traverse the edge the same way
  double surface_area = 0.0;
  double enclosed_volume = 0.0;  // signed, divergence theorem; < 0: inward normals
  bool watertight() const { return boundary_edges == 0 && non_manifold_edges == 0 && inconsistent_edges == 0; }
};

// Vertices at identical positions are welded before edges are counted, so a triangle
// soup (STL) is judged by its geometry, not by its index buffer.
MeshReport validate_mesh(const Mesh& mesh);

// Human-readable multi-line text, and one JSON object, of the same report.
std::string format_mesh_report(const MeshReport& report);
std::string mesh_report_json(const MeshReport& report);

}  // namespace snapfit
