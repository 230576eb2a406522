#include "engine/fields/winding_propagation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>
#include <unordered_map>

#include "snapfit/error.h"

namespace snapfit {
namespace {

// Union-find with path halving and union by index (deterministic).
struct DisjointSets {
  std::vector<std::int32_t> parent;
  explicit DisjointSets(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  std::int32_t find(std::int32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(std::int32_t a, std::int32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (a < b) std::swap(a, b);
    parent[a] = b;
  }
};

struct Vec3Hash {
  std::size_t operator()(const Eigen::Vector3d& v) const {
    std::uint64_t h = 1469598103934665603ull;
    for (int k = 0; k < 3; ++k) {
      double x = v[k] == 0.0 ? 0.0 : v[k];  // +0 and -0 are the same point
      std::uint64_t bits;
      std::memcpy(&bits, &x, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
    }
    return static_cast<std::size_t>(h);
  }
};

}  // namespace

bool mesh_is_closed(const Mesh& mesh) {
  if (mesh.triangles.empty()) return false;
  // Weld vertices with exactly equal coordinates.
  std::unordered_map<Eigen::Vector3d, std::int64_t, Vec3Hash> ids;
  ids.reserve(mesh.vertices.size());
  std::vector<std::int64_t> welded(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i)
    welded[i] = ids.emplace(mesh.vertices[i], static_cast<std::int64_t>(ids.size())).first->second;
  // Balance of each undirected edge: +1 for lo->hi, -1 for hi->lo. The boundary of the
  // triangle chain is empty exactly when every balance is 0.
  std::unordered_map<std::uint64_t, int> balance;
  balance.reserve(3 * mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    for (int k = 0; k < 3; ++k) {
      const int ia = t[k], ib = t[(k + 1) % 3];
      if (ia < 0 || ib < 0 || ia >= static_cast<int>(welded.size()) || ib >= static_cast<int>(welded.size()))
        return false;
      const std::int64_t a = welded[ia], b = welded[ib];
      if (a == b) continue;
      const std::uint64_t key =
          (static_cast<std::uint64_t>(std::min(a, b)) << 32) | static_cast<std::uint64_t>(std::max(a, b));
      balance[key] += a < b ? 1 : -1;
    }
  }
  for (const auto& [edge, count] : balance)
    if (count != 0) return false;
  return true;
}

double distance_rounding_slack(const GridSpec& grid, const Mesh& mesh) {
  double magnitude = 0;
  for (int a = 0; a < 3; ++a)
    magnitude = std::max({magnitude, std::abs(grid.origin[a]), std::abs(grid.origin[a] + grid.spacing * grid.dims[a])});
  for (const Eigen::Vector3d& v : mesh.vertices) magnitude = std::max(magnitude, v.cwiseAbs().maxCoeff());
  // Grid points, vertices and the point-triangle distance are float: a few dozen
  // float steps (2^-23) of the largest coordinate, and of the spacing, cover them.
  return 32.0 * 1.1920929e-7 * (magnitude + grid.spacing);
}

WindingComponents winding_components(const GridSpec& grid, const std::vector<float>& distance, double slack) {
  const std::size_t count = grid.count();
  if (distance.size() != count) throw Error("winding propagation: distance field does not match the grid");
  if (count > static_cast<std::size_t>(INT32_MAX)) throw Error("winding propagation: grid too large");
  const int nx = grid.dims.x(), ny = grid.dims.y(), nz = grid.dims.z();
  const double limit = grid.spacing + slack;
  DisjointSets sets(count);
  auto link = [&](std::size_t a, std::size_t b) {
    if (static_cast<double>(distance[a]) + static_cast<double>(distance[b]) > limit)
      sets.unite(static_cast<std::int32_t>(a), static_cast<std::int32_t>(b));
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t idx = grid.index(i, j, k);
        if (i + 1 < nx) link(idx, idx + 1);
        if (j + 1 < ny) link(idx, idx + static_cast<std::size_t>(nx));
        if (k + 1 < nz) link(idx, idx + static_cast<std::size_t>(nx) * ny);
      }
  WindingComponents out;
  out.component.resize(count);
  // Roots are the smallest index of their set (union by index), so a root is met
  // before the other members and numbering follows grid order.
  for (std::size_t idx = 0; idx < count; ++idx) {
    const std::int32_t root = sets.find(static_cast<std::int32_t>(idx));
    if (root == static_cast<std::int32_t>(idx)) {
      out.component[idx] = static_cast<std::int32_t>(out.seeds.size());
      out.seeds.push_back(static_cast<std::int64_t>(idx));
    } else {
      out.component[idx] = out.component[root];
      const std::int64_t seed = out.seeds[out.component[idx]];
      if (distance[idx] > distance[seed]) out.seeds[out.component[idx]] = static_cast<std::int64_t>(idx);
    }
  }
  return out;
}

std::size_t propagate_winding(const WindingComponents& components, const std::vector<float>& seed_winding,
                              const std::vector<float>& seed_bound, std::vector<float>& winding,
                              std::vector<float>& winding_bound) {
  const std::size_t n = components.seeds.size();
  if (seed_winding.size() != n || seed_bound.size() != n)
    throw Error("winding propagation: one value per component expected");
  std::vector<float> value(n), bound(n);
  std::size_t proven = 0;
  for (std::size_t c = 0; c < n; ++c) {
    const double w = seed_winding[c], b = seed_bound[c];
    const double k = std::nearbyint(w);
    // The exact w is an integer within b of the computed one (to float rounding of
    // the kernel's sum, which the 0.01 margin covers): it is k when |w - k| + b < 1/2.
    if (std::isfinite(w) && std::isfinite(b) && std::abs(w - k) + b < 0.49) {
      value[c] = static_cast<float>(k);
      bound[c] = 0.0f;
      ++proven;
    } else {
      value[c] = seed_winding[c];
      bound[c] = seed_bound[c];
    }
  }
  const std::size_t count = components.component.size();
  winding.resize(count);
  winding_bound.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    winding[i] = value[components.component[i]];
    winding_bound[i] = bound[components.component[i]];
  }
  return proven;
}

}  // namespace snapfit
