#include "engine/fields/sphere_decomposition.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>
#include <string>

#include "core/progress.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

Eigen::AlignedBox3d mesh_box(const Mesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) box.extend(mesh.vertices[static_cast<std::size_t>(t[c])]);
  return box;
}

// Step 1 of Algorithm 1: A1, the balls at the selected nodes (radius = distance to the
// boundary), until every inside node lies in one of them.
std::vector<Ball> greedy_cover(const GridSpec& grid, const std::vector<std::size_t>& inside,
                               const std::vector<float>& radius_at, const std::vector<float>& priority,
                               double protrusion) {
  std::vector<std::size_t> order = inside;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return priority[a] > priority[b]; });
  std::vector<char> is_inside(grid.count(), 0), covered(grid.count(), 0), popped(grid.count(), 0);
  for (std::size_t id : inside) is_inside[id] = 1;
  std::size_t covered_count = 0;
  std::vector<Ball> balls;
  const Eigen::Vector3i& n = grid.dims;
  for (std::size_t next = 0; covered_count < inside.size() && next < order.size(); ++next) {
    const std::size_t id = order[next];
    if (popped[id]) continue;
    const double r = radius_at[id];
    const int i0 = static_cast<int>(id % static_cast<std::size_t>(n.x()));
    const int j0 = static_cast<int>(id / static_cast<std::size_t>(n.x()) % static_cast<std::size_t>(n.y()));
    const int k0 = static_cast<int>(id / (static_cast<std::size_t>(n.x()) * static_cast<std::size_t>(n.y())));
    balls.push_back({grid.point(i0, j0, k0), r});
    // Every node the ball covers or pops lies within distance r of its centre
    // (d <= r - (1 - mu) r' <= r for both tests).
    const int reach = static_cast<int>(std::floor(r / grid.spacing));
    for (int k = std::max(0, k0 - reach); k <= std::min(n.z() - 1, k0 + reach); ++k)
      for (int j = std::max(0, j0 - reach); j <= std::min(n.y() - 1, j0 + reach); ++j)
        for (int i = std::max(0, i0 - reach); i <= std::min(n.x() - 1, i0 + reach); ++i) {
          const std::size_t other = grid.index(i, j, k);
          if (!is_inside[other]) continue;
          const double d =
              grid.spacing * std::sqrt(double((i - i0) * (i - i0) + (j - j0) * (j - j0) + (k - k0) * (k - k0)));
          if (d > r) continue;
          if (!covered[other]) {
            covered[other] = 1;
            ++covered_count;
          }
          const double r_other = radius_at[other];
          if (d + r_other - r <= protrusion * r_other) popped[other] = 1;  // (A.1), see the header
        }
    if (!covered[id]) {  // a node closer to the boundary than a cell still covers itself
      covered[id] = 1;
      ++covered_count;
    }
  }
  return balls;
}

// Steps 2 and 3: expand every ball by epsilon (A.2), then keep, by decreasing radius,
// those whose unexpanded ball no kept expanded ball contains (A.4).
std::vector<Ball> expand_and_reduce(std::vector<Ball> sampled, double epsilon) {
  std::stable_sort(sampled.begin(), sampled.end(), [](const Ball& a, const Ball& b) { return a.radius > b.radius; });
  std::vector<Ball> kept;
  for (const Ball& b : sampled) {
    bool engulfed = false;
    for (const Ball& k : kept)
      if ((k.centre - b.centre).norm() <= k.radius - b.radius) {
        engulfed = true;
        break;
      }
    if (!engulfed) kept.push_back({b.centre, b.radius + epsilon});
  }
  return kept;
}

}  // namespace

SphereDecomposition decompose_into_balls(const GridSpec& grid, const std::vector<float>& winding,
                                         const std::vector<float>& signed_distance, const std::vector<float>& priority,
                                         double epsilon, double protrusion) {
  const std::size_t m = grid.count();
  if (winding.size() != m || signed_distance.size() != m || priority.size() != m)
    throw Error("spherical decomposition: the fields do not match the grid (" + std::to_string(m) + " points)");
  if (!(protrusion >= 0 && protrusion <= 1))
    throw Error("spherical decomposition: protrusion must be in [0, 1] (got " + std::to_string(protrusion) + ")");
  if (!(epsilon > 0) || !std::isfinite(epsilon))
    throw Error("spherical decomposition: tolerance must be a positive number");
  std::vector<std::size_t> inside;
  std::vector<float> radius(m, 0.0f);
  for (std::size_t id = 0; id < m; ++id)
    if (winding[id] >= 0.5f && std::isfinite(signed_distance[id])) {
      inside.push_back(id);
      radius[id] = std::abs(signed_distance[id]);
    }
  if (inside.empty())
    throw Error("spherical decomposition: no grid node lies inside the part at spacing " +
                std::to_string(grid.spacing) + "; use a smaller tolerance");
  SphereDecomposition out;
  const std::vector<Ball> sampled = greedy_cover(grid, inside, radius, priority, protrusion);
  out.sampled_balls = sampled.size();
  out.balls = expand_and_reduce(sampled, epsilon);
  out.grid_nodes = m;
  out.inside_nodes = inside.size();
  out.spacing = grid.spacing;
  out.epsilon = epsilon;
  return out;
}

GridSpec sphere_grid(const Mesh& mesh, double tolerance) {
  if (!(tolerance > 0) || !std::isfinite(tolerance))
    throw Error("spherical decomposition: tolerance must be a positive number (got " + std::to_string(tolerance) + ")");
  if (mesh.empty()) throw Error("spherical decomposition: the mesh is empty");
  GridParams params;
  params.spacing = 2.0 * tolerance / std::sqrt(3.0);
  params.padding = *params.spacing;
  return make_grid(mesh_box(mesh), params);
}

SphereDecomposition decompose_part(const ComputeContext& ctx, const Mesh& mesh, const DescriptorParams& descriptor,
                                   const SphereDecompositionParams& params, const DescriptorOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  const GridSpec grid = sphere_grid(mesh, params.tolerance);
  DescriptorParams sdf = descriptor;
  sdf.kind = DescriptorKind::skeletal_density;
  const DescriptorFields fields = compute_descriptors(ctx, mesh, grid, sdf, options);
  const double field_seconds = seconds_since(start);
  std::vector<float> distance_priority;
  if (params.order == BallOrder::distance) {
    distance_priority.resize(fields.signed_distance.size());
    for (std::size_t i = 0; i < distance_priority.size(); ++i) distance_priority[i] = -fields.signed_distance[i];
  }
  SphereDecomposition out =
      decompose_into_balls(grid, fields.winding, fields.signed_distance,
                           params.order == BallOrder::distance ? distance_priority : fields.skeletal_density,
                           params.tolerance, params.protrusion);
  out.field_seconds = field_seconds;
  out.seconds = seconds_since(start);
  return out;
}

}  // namespace snapfit
