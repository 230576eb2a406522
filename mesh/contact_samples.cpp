#include "mesh/contact_samples.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <array>
#include <cstdint>
#include <map>
#include <unordered_map>
#include <numeric>
#include <utility>

#include "mesh/cell_key.h"
#include "mesh/triangle_refine.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

// The mesh's sharp edges as vertex pairs: two triangles meeting at more than the angle
// between their normals, or an edge with one triangle (an open boundary).
std::vector<std::pair<int, int>> sharp_edges(const Mesh& mesh, double sharp_angle_deg) {
  std::map<std::pair<int, int>, std::vector<Eigen::Vector3d>> normals;  // undirected edge -> adjacent normals
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d n = (mesh.vertices[t[1]] - mesh.vertices[t[0]]).cross(mesh.vertices[t[2]] - mesh.vertices[t[0]]);
    const double len = n.norm();
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      normals[{std::min(a, b), std::max(a, b)}].push_back(len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero());
    }
  }
  const double cos_sharp = std::cos(sharp_angle_deg * M_PI / 180);
  std::vector<std::pair<int, int>> out;
  for (const auto& [edge, ns] : normals) {
    bool sharp = ns.size() != 2;
    for (std::size_t i = 0; i < ns.size() && !sharp; ++i)
      for (std::size_t j = i + 1; j < ns.size() && !sharp; ++j) sharp = ns[i].dot(ns[j]) < cos_sharp;
    if (sharp) out.push_back(edge);
  }
  return out;
}

// Groups the points into chunks of cubes `size` across, reordering points and areas.
void chunk(ContactSamples& s, double size) {
  if (s.points.empty()) return;
  Eigen::Vector3d lo = s.points[0];
  for (const Eigen::Vector3d& p : s.points) lo = lo.cwiseMin(p);
  std::vector<std::array<long, 3>> key(s.points.size());
  for (std::size_t i = 0; i < s.points.size(); ++i)
    for (int a = 0; a < 3; ++a) key[i][a] = static_cast<long>(std::floor((s.points[i][a] - lo[a]) / size));
  std::vector<std::size_t> order(s.points.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return key[a] < key[b]; });
  ContactSamples sorted = s;
  for (std::size_t i = 0; i < order.size(); ++i) sorted.points[i] = s.points[order[i]], sorted.areas[i] = s.areas[order[i]];
  sorted.chunks.clear();
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin;
    while (end < order.size() && key[order[end]] == key[order[begin]]) ++end;
    ShellChunk c;
    c.begin = begin, c.end = end;
    for (std::size_t i = begin; i < end; ++i) c.centre += sorted.points[i];
    c.centre /= double(end - begin);
    for (std::size_t i = begin; i < end; ++i) c.radius = std::max(c.radius, (sorted.points[i] - c.centre).norm());
    sorted.chunks.push_back(c);
    begin = end;
  }
  s = std::move(sorted);
}

}  // namespace

ContactSamples build_contact_samples(const Mesh& mesh, double spacing, bool features_only, double sharp_angle_deg) {
  if (mesh.empty()) throw Error("contact samples: the mesh has no triangles");
  if (!(std::isfinite(spacing) && spacing > 0)) throw Error("contact samples: spacing must be > 0");
  ContactSamples s;
  s.spacing = spacing;
  if (!features_only) {
    // Candidates: the centroids of the surface cut into pieces within spacing / 4 of
    // them; one point per cell of `spacing`: the candidate nearest the cell's centre,
    // standing for the area of all the cell's candidates. Any tessellation, fine or
    // coarse, gives about one point per spacing^2 of surface.
    const Mesh pieces = refine_triangles(mesh, 0.25 * spacing);
    std::unordered_map<std::uint64_t, std::size_t> cell_point;  // cell -> index in s.points
    std::vector<double> nearest;                                // squared distance of each point to its cell's centre
    for (const Eigen::Vector3i& t : pieces.triangles) {
      const Eigen::Vector3d &a = pieces.vertices[t[0]], &b = pieces.vertices[t[1]], &c = pieces.vertices[t[2]];
      const double area = 0.5 * (b - a).cross(c - a).norm();
      if (!(area > 0)) continue;
      const Eigen::Vector3d centroid = (a + b + c) / 3.0;
      Eigen::Vector3d centre;
      const std::uint64_t key = cell_key(centroid, spacing, centre);
      const double d2 = (centroid - centre).squaredNorm();
      const auto [it, fresh] = cell_point.emplace(key, s.points.size());
      if (fresh) {
        s.points.push_back(centroid);
        s.areas.push_back(area);
        nearest.push_back(d2);
        continue;
      }
      s.areas[it->second] += area;
      if (d2 < nearest[it->second]) nearest[it->second] = d2, s.points[it->second] = centroid;
    }
    s.face_points = s.points.size();
  }
  std::vector<int> corners;  // the sharp edges' ends, each once
  for (const auto& [a, b] : sharp_edges(mesh, sharp_angle_deg)) {
    const Eigen::Vector3d &p = mesh.vertices[a], &q = mesh.vertices[b];
    const int n = std::max(1, static_cast<int>(std::ceil((q - p).norm() / spacing)));
    for (int i = 1; i < n; ++i) {
      s.points.push_back(p + (q - p) * (double(i) / n));
      s.areas.push_back(spacing * spacing);
    }
    corners.push_back(a), corners.push_back(b);
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  for (int v : corners) {
    s.points.push_back(mesh.vertices[v]);
    s.areas.push_back(spacing * spacing);
  }
  s.feature_points = s.points.size() - s.face_points;
  chunk(s, 8 * spacing);
  return s;
}

ContactSamples samples_inside(const ContactSamples& samples, const Eigen::AlignedBox3d& box) {
  ContactSamples out;
  out.spacing = samples.spacing;
  for (std::size_t i = 0; i < samples.points.size(); ++i) {
    if (!box.contains(samples.points[i])) continue;
    out.points.push_back(samples.points[i]);
    out.areas.push_back(samples.areas[i]);
  }
  // The kinds are told apart by the area a feature point stands for (spacing^2, exactly).
  const double feature_area = samples.spacing * samples.spacing;
  for (double a : out.areas) ++(a == feature_area && samples.feature_points ? out.feature_points : out.face_points);
  chunk(out, 8 * samples.spacing);
  return out;
}

}  // namespace snapfit
