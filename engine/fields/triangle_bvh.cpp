#include "engine/fields/triangle_bvh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <atomic>
#include <numeric>
#include <tbb/task_group.h>

#include "snapfit/error.h"

namespace snapfit {
namespace {

using Vec3 = Eigen::Vector3d;

struct TriangleData {
  Vec3 v[3];
  Vec3 centroid;
  Vec3 area_normal;  // A_t n_t = (v1 - v0) x (v2 - v0) / 2
  double area;
};

// Number of nodes of the subtree over n triangles (median splits are deterministic),
// which lets both halves be written in parallel at known offsets.
int subtree_size(int n, int leaf_size) {
  if (n <= leaf_size) return 1;
  return 1 + subtree_size(n / 2, leaf_size) + subtree_size(n - n / 2, leaf_size);
}

cl_float4 f4(const Vec3& v, double w = 0.0) {
  return cl_float4{
      {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()), static_cast<float>(w)}};
}

struct Builder {
  const std::vector<TriangleData>& tris;
  std::vector<int>& order;  // triangle indices, permuted into leaf order
  std::vector<BvhNode>& nodes;
  int leaf_size;
  std::atomic<int> depth{0};

  void build(int node, int first, int count, int level, tbb::task_group* group) {
    int seen = depth.load();
    while (level > seen && !depth.compare_exchange_weak(seen, level)) {
    }
    // Moments of the node (Barill et al. 2018, sec. 3.2, order 0 and 1).
    Eigen::AlignedBox3d box;
    double area = 0;
    Vec3 weighted = Vec3::Zero(), normal = Vec3::Zero();
    for (int i = first; i < first + count; ++i) {
      const TriangleData& t = tris[order[i]];
      for (const Vec3& v : t.v) box.extend(v);
      area += t.area;
      weighted += t.area * t.centroid;
      normal += t.area_normal;
    }
    const Vec3 c = area > 0 ? Vec3(weighted / area) : box.center();
    double radius = 0, second = 0;
    Eigen::Matrix3d moment = Eigen::Matrix3d::Zero();
    for (int i = first; i < first + count; ++i) {
      const TriangleData& t = tris[order[i]];
      for (const Vec3& v : t.v) radius = std::max(radius, (v - c).norm());
      moment += t.area_normal * (t.centroid - c).transpose();
      // integral over the triangle of |q - c|^2 dA = A |c_t - c|^2 + (A/12) sum_i |v_i - c_t|^2
      // (the covariance of a uniform triangle is (1/12) sum_i (v_i - c_t)(v_i - c_t)^T).
      double spread = 0;
      for (const Vec3& v : t.v) spread += (v - t.centroid).squaredNorm();
      second += t.area * ((t.centroid - c).squaredNorm() + spread / 12.0);
    }
    BvhNode& out = nodes[node];
    out.bbox_min = f4(box.min(), area);
    // The kernels see float centroids and vertices: grow the ball by their rounding
    // (a few float steps at the coordinates' magnitude), so it still holds every vertex.
    const double magnitude = std::max(box.min().cwiseAbs().maxCoeff(), box.max().cwiseAbs().maxCoeff());
    const double slack = radius * 1e-6 + 8.0 * 1.2e-7 * magnitude;
    out.bbox_max = f4(box.max(), radius + slack);
    // The second moment grows likewise: |q - c| + slack under the integral, and
    // integral |q - c| dA <= sqrt(A I) (Cauchy-Schwarz).
    out.centroid = f4(c, second * (1.0 + 1e-6) + 2.0 * slack * std::sqrt(area * second) + area * slack * slack);
    out.area_normal = f4(normal);
    for (int row = 0; row < 3; ++row) out.moment[row] = f4(moment.row(row).transpose());

    if (count <= leaf_size) {
      out.links = cl_int4{{-1, first, count, 0}};
      return;
    }
    // Median split along the longest axis of the centroids' box.
    Eigen::AlignedBox3d cbox;
    for (int i = first; i < first + count; ++i) cbox.extend(tris[order[i]].centroid);
    int axis;
    cbox.sizes().maxCoeff(&axis);
    const int half = count / 2;
    std::nth_element(order.begin() + first, order.begin() + first + half, order.begin() + first + count,
                     [&](int a, int b) { return tris[a].centroid[axis] < tris[b].centroid[axis]; });
    const int left = node + 1;
    const int right = left + subtree_size(half, leaf_size);
    out.links = cl_int4{{right, first, count, 0}};
    if (group && count > 20000) {
      group->run([=] { build(left, first, half, level + 1, group); });
      group->run([=] { build(right, first + half, count - half, level + 1, group); });
    } else {
      build(left, first, half, level + 1, nullptr);
      build(right, first + half, count - half, level + 1, nullptr);
    }
  }
};

}  // namespace

TriangleBvh build_triangle_bvh(const Mesh& mesh, int leaf_size) {
  if (mesh.triangles.empty()) throw Error("cannot build a triangle hierarchy over an empty mesh");
  if (leaf_size < 1) throw Error("BVH leaf size must be at least 1");
  const int n = static_cast<int>(mesh.triangles.size());
  std::vector<TriangleData> tris(n);
  for (int i = 0; i < n; ++i) {
    TriangleData& t = tris[i];
    for (int k = 0; k < 3; ++k) {
      const int idx = mesh.triangles[i][k];
      if (idx < 0 || idx >= static_cast<int>(mesh.vertices.size()))
        throw Error("triangle " + std::to_string(i) + " has an out-of-range vertex index");
      t.v[k] = mesh.vertices[idx];
    }
    t.centroid = (t.v[0] + t.v[1] + t.v[2]) / 3.0;
    t.area_normal = 0.5 * (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
    t.area = t.area_normal.norm();
  }
  TriangleBvh bvh;
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  bvh.nodes.resize(subtree_size(n, leaf_size));
  Builder builder{tris, order, bvh.nodes, leaf_size};
  tbb::task_group group;
  group.run_and_wait([&] { builder.build(0, 0, n, 1, &group); });
  group.wait();
  bvh.depth = builder.depth.load();
  bvh.triangles.reserve(3 * static_cast<std::size_t>(n));
  for (int i : order) {
    for (const Vec3& v : tris[i].v) bvh.triangles.push_back(f4(v));
    bvh.total_area += tris[i].area;
  }
  return bvh;
}

}  // namespace snapfit
