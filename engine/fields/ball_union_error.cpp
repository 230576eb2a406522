#include "engine/fields/ball_union_error.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <random>

#include "mesh/mesh_mass_properties.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

Eigen::AlignedBox3d ball_box(const Ball& b) {
  return Eigen::AlignedBox3d(b.centre.array() - b.radius, b.centre.array() + b.radius);
}

// The 95 % Wilson score interval of a binomial proportion k / n.
std::pair<double, double> wilson95(std::size_t k, std::size_t n) {
  const double z = 1.959963984540054, p = double(k) / double(n), nn = double(n);
  const double centre = (p + z * z / (2 * nn)) / (1 + z * z / nn);
  const double half = z * std::sqrt(p * (1 - p) / nn + z * z / (4 * nn * nn)) / (1 + z * z / nn);
  return {std::max(0.0, centre - half), std::min(1.0, centre + half)};
}

}  // namespace

std::vector<char> inside_ball_union(const std::vector<Ball>& balls, const std::vector<Eigen::Vector3d>& points) {
  std::vector<char> inside(points.size(), 0);
  if (balls.empty() || points.empty()) return inside;
  Eigen::AlignedBox3d box;
  for (const Ball& b : balls) box.extend(ball_box(b));
  const int cells = std::clamp(static_cast<int>(std::cbrt(double(balls.size()))) * 2, 1, 48);
  const Eigen::Vector3d lo = box.min(), size = (box.max() - box.min()).cwiseMax(1e-300) / cells;
  auto cell_of = [&](const Eigen::Vector3d& p) {
    Eigen::Vector3i c;
    for (int a = 0; a < 3; ++a) c[a] = std::clamp(static_cast<int>(std::floor((p[a] - lo[a]) / size[a])), 0, cells - 1);
    return c;
  };
  std::vector<std::vector<int>> bucket(static_cast<std::size_t>(cells) * cells * cells);
  for (std::size_t i = 0; i < balls.size(); ++i) {
    const Eigen::AlignedBox3d bb = ball_box(balls[i]);
    const Eigen::Vector3i a = cell_of(bb.min()), b = cell_of(bb.max());
    for (int z = a.z(); z <= b.z(); ++z)
      for (int y = a.y(); y <= b.y(); ++y)
        for (int x = a.x(); x <= b.x(); ++x)
          bucket[static_cast<std::size_t>(x + cells * (y + cells * z))].push_back(static_cast<int>(i));
  }
  for (std::size_t p = 0; p < points.size(); ++p) {
    if (!box.contains(points[p])) continue;
    const Eigen::Vector3i c = cell_of(points[p]);
    for (int i : bucket[static_cast<std::size_t>(c.x() + cells * (c.y() + cells * c.z()))]) {
      const Ball& b = balls[static_cast<std::size_t>(i)];
      if ((points[p] - b.centre).squaredNorm() <= b.radius * b.radius) {
        inside[p] = 1;
        break;
      }
    }
  }
  return inside;
}

BallUnionError ball_union_error(const ComputeContext& ctx, const Mesh& mesh, const std::vector<Ball>& balls,
                                std::size_t samples, std::uint64_t seed, const DescriptorOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  if (mesh.empty()) throw Error("ball union error: the mesh is empty");
  if (balls.empty()) throw Error("ball union error: no balls");
  if (samples == 0) throw Error("ball union error: needs at least one sample");
  Eigen::AlignedBox3d box;
  for (const Eigen::Vector3i& t : mesh.triangles)
    for (int c = 0; c < 3; ++c) box.extend(mesh.vertices[static_cast<std::size_t>(t[c])]);
  for (const Ball& b : balls) box.extend(ball_box(b));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Eigen::Vector3d> points(samples);
  const Eigen::Vector3d extent = box.max() - box.min();
  for (Eigen::Vector3d& p : points)
    p = box.min() + Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).cwiseProduct(extent);

  DescriptorParams indicator;
  indicator.kind = DescriptorKind::indicator;
  DescriptorOptions opt = options;
  opt.indicator_signed_distance = true;
  const DescriptorFields solid =
      descriptors_at_points(ctx, mesh, points, box.min(), extent.maxCoeff() / 64.0, indicator, opt);
  const std::vector<char> in_union = inside_ball_union(balls, points);

  BallUnionError out;
  out.samples = samples;
  out.sample_box_volume = extent.prod();
  out.solid_volume = std::abs(solid_moments(mesh).volume);
  for (std::size_t i = 0; i < samples; ++i) {
    const bool in_solid = solid.winding[i] >= 0.5f;
    if (in_solid == static_cast<bool>(in_union[i])) continue;
    ++out.mismatched;
    double distance = std::abs(static_cast<double>(solid.signed_distance[i]));  // in U, not in S: to S
    if (in_solid) {                                                             // in S, not in U: to U
      distance = std::numeric_limits<double>::infinity();
      for (const Ball& b : balls) distance = std::min(distance, (points[i] - b.centre).norm() - b.radius);
    }
    out.hausdorff_sampled = std::max(out.hausdorff_sampled, distance);
  }
  const auto [low, high] = wilson95(out.mismatched, samples);
  out.volume_error = out.sample_box_volume * double(out.mismatched) / double(samples);
  out.volume_error_low = out.sample_box_volume * low;
  out.volume_error_high = out.sample_box_volume * high;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace snapfit
