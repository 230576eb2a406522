// Mesh validation report (mesh/mesh_report.h).
#include "mesh/mesh_report.h"

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <iomanip>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>
#include <vector>

#include "snapfit/error.h"

namespace snapfit {
namespace {

// Welded index of every vertex: vertices at exactly equal positions share one index.
// std::map compares with <, so -0.0 and +0.0 weld; non-finite vertices stay apart.
std::vector<int> weld(const std::vector<Eigen::Vector3d>& vertices, std::size_t& distinct) {
  std::map<std::array<double, 3>, int> first;
  std::vector<int> id(vertices.size());
  int next = 0;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Eigen::Vector3d& v = vertices[i];
    if (!v.allFinite()) {
      id[i] = next++;
      continue;
    }
    const auto [it, inserted] = first.emplace(std::array<double, 3>{v.x(), v.y(), v.z()}, next);
    id[i] = it->second;
    if (inserted) ++next;
  }
  distinct = static_cast<std::size_t>(next);
  return id;
}

// Uses of an undirected edge (a < b): how many triangles traverse it a->b and b->a.
struct EdgeUse {
  int forward = 0;
  int backward = 0;
};

}  // namespace

MeshReport validate_mesh(const Mesh& mesh) {
  MeshReport r;
  r.triangle_count = mesh.triangles.size();
  const int n = static_cast<int>(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (mesh.triangles[t][k] < 0 || mesh.triangles[t][k] >= n)
        throw Error("mesh: triangle " + std::to_string(t) + " refers to vertex " +
                    std::to_string(mesh.triangles[t][k]) + " but there are " + std::to_string(n) + " vertices");

  const std::vector<int> id = weld(mesh.vertices, r.vertex_count);
  if (!mesh.vertices.empty()) {
    r.bbox_min = r.bbox_max = mesh.vertices.front();
    for (const auto& v : mesh.vertices) {
      r.bbox_min = r.bbox_min.cwiseMin(v);
      r.bbox_max = r.bbox_max.cwiseMax(v);
    }
  }
  const double diag2 = (r.bbox_max - r.bbox_min).squaredNorm();

  std::map<std::pair<int, int>, EdgeUse> edges;
  for (const auto& tri : mesh.triangles) {
    const Eigen::Vector3d& v0 = mesh.vertices[tri[0]];
    const Eigen::Vector3d& v1 = mesh.vertices[tri[1]];
    const Eigen::Vector3d& v2 = mesh.vertices[tri[2]];
    const double area = 0.5 * (v1 - v0).cross(v2 - v0).norm();
    r.surface_area += area;
    // Divergence theorem: V = sum over triangles of det(v0, v1, v2) / 6 (signed tetrahedra
    // with apex at the origin). Exact for a closed mesh; for an open one it depends on
    // the origin, which is why the text report warns.
    r.enclosed_volume += v0.dot(v1.cross(v2)) / 6.0;

    const int a = id[tri[0]], b = id[tri[1]], d = id[tri[2]];
    const bool repeated = (a == b || b == d || d == a);
    if (repeated || area <= 1e-12 * diag2) ++r.degenerate_triangles;
    // A triangle with a repeated welded vertex has no well-defined edges; zero-area
    // triangles with distinct vertices keep theirs (they still connect the surface).
    if (repeated) continue;
    const std::array<std::pair<int, int>, 3> directed{{{a, b}, {b, d}, {d, a}}};
    for (const auto& [from, to] : directed) {
      EdgeUse& use = edges[{std::min(from, to), std::max(from, to)}];
      if (from < to)
        ++use.forward;
      else
        ++use.backward;
    }
  }
  for (const auto& [key, use] : edges) {
    const int total = use.forward + use.backward;
    if (total == 1)
      ++r.boundary_edges;
    else if (total > 2)
      ++r.non_manifold_edges;
    else if (use.forward != 1)
      ++r.inconsistent_edges;  // total 2, same direction twice
  }
  return r;
}

std::string format_mesh_report(const MeshReport& r) {
  std::ostringstream s;
  s << std::setprecision(9);
  auto vec = [&s](const Eigen::Vector3d& v) { s << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")"; };
  s << "vertices: " << r.vertex_count << " (distinct positions)\n";
  s << "triangles: " << r.triangle_count << "\n";
  s << "bounding box: min ";
  vec(r.bbox_min);
  s << " max ";
  vec(r.bbox_max);
  s << " size ";
  vec(r.bbox_max - r.bbox_min);
  s << "\n";
  s << "degenerate triangles: " << r.degenerate_triangles << "\n";
  s << "boundary edges: " << r.boundary_edges << "\n";
  s << "non-manifold edges: " << r.non_manifold_edges << "\n";
  s << "inconsistently oriented edges: " << r.inconsistent_edges << "\n";
  s << "watertight: " << (r.watertight() ? "yes" : "no") << "\n";
  s << "surface area: " << r.surface_area << "\n";
  s << "enclosed volume: " << r.enclosed_volume << "\n";
  if (r.enclosed_volume < 0.0)
    s << "warning: enclosed volume is negative: normals point inward (triangles wound clockwise seen from outside)\n";
  if (!r.watertight()) s << "warning: mesh is not watertight: enclosed volume is not well defined\n";
  if (r.degenerate_triangles > 0) s << "warning: " << r.degenerate_triangles << " degenerate triangle(s)\n";
  return s.str();
}

std::string mesh_report_json(const MeshReport& r) {
  auto arr = [](const Eigen::Vector3d& v) { return nlohmann::json::array({v.x(), v.y(), v.z()}); };
  const nlohmann::json j = {
      {"vertex_count", r.vertex_count},
      {"triangle_count", r.triangle_count},
      {"bbox_min", arr(r.bbox_min)},
      {"bbox_max", arr(r.bbox_max)},
      {"degenerate_triangles", r.degenerate_triangles},
      {"boundary_edges", r.boundary_edges},
      {"non_manifold_edges", r.non_manifold_edges},
      {"inconsistent_edges", r.inconsistent_edges},
      {"watertight", r.watertight()},
      {"surface_area", r.surface_area},
      {"enclosed_volume", r.enclosed_volume},
  };
  return j.dump();  // no indent: one line
}

}  // namespace snapfit
