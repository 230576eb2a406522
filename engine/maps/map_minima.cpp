#include "engine/maps/map_minima.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "snapfit/error.h"

namespace snapfit {
namespace {

// True when e[g] is a local minimum: below every neighbour before g in grid order and
// below or equal to every one after it (a plateau's first point).
bool is_minimum(const GridSpec& grid, const std::vector<float>& e, int x, int y, int z) {
  const std::size_t g = grid.index(x, y, z);
  const float v = e[g];
  for (int dz = -1; dz <= 1; ++dz) {
    const int zz = z + dz;
    if (zz < 0 || zz >= grid.dims.z()) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      const int yy = y + dy;
      if (yy < 0 || yy >= grid.dims.y()) continue;
      for (int dx = -1; dx <= 1; ++dx) {
        const int xx = x + dx;
        if (xx < 0 || xx >= grid.dims.x() || (dx == 0 && dy == 0 && dz == 0)) continue;
        const std::size_t n = grid.index(xx, yy, zz);
        const float w = e[n];
        if (std::isnan(w)) continue;
        if (w < v || (w == v && n < g)) return false;
      }
    }
  }
  return true;
}

}  // namespace

std::vector<MapMinimum> map_minima(const GridSpec& grid, const std::vector<float>& energy, std::size_t count,
                                   double separation) {
  if (energy.size() != grid.count()) throw Error("map_minima: the energy has a size other than the grid's");
  std::vector<MapMinimum> candidates;
  if (count == 0) return candidates;
  for (int z = 0; z < grid.dims.z(); ++z)
    for (int y = 0; y < grid.dims.y(); ++y)
      for (int x = 0; x < grid.dims.x(); ++x) {
        const std::size_t g = grid.index(x, y, z);
        const float v = energy[g];
        // Cheap rejections first: most points have a lower x neighbour.
        if (!(v < 0)) continue;
        if (x > 0 && energy[g - 1] <= v) continue;
        if (x + 1 < grid.dims.x() && energy[g + 1] < v) continue;
        if (!is_minimum(grid, energy, x, y, z)) continue;
        candidates.push_back({g, grid.point(x, y, z), v});
      }
  std::vector<MapMinimum> kept;
  thin_minima(candidates, count, separation, kept);
  return kept;
}

void map_minima(const GridSpec& grid, const std::vector<float>& energy, std::size_t count, double separation,
                MapMinimaResult& out) {
  float best = std::numeric_limits<float>::quiet_NaN();
  for (float e : energy)
    if (std::isfinite(e) && !(e >= best)) best = e;
  out.minima = map_minima(grid, energy, count, separation);
  out.best = best;
}

void thin_minima(std::vector<MapMinimum>& candidates, std::size_t count, double separation,
                 std::vector<MapMinimum>& kept) {
  kept.clear();
  std::sort(candidates.begin(), candidates.end(), [](const MapMinimum& a, const MapMinimum& b) {
    return a.energy < b.energy || (a.energy == b.energy && a.index < b.index);
  });
  const double s2 = separation * separation;
  for (const MapMinimum& c : candidates) {
    if (kept.size() == count) break;
    const bool near = std::any_of(kept.begin(), kept.end(), [&](const MapMinimum& k) {
      return (k.translation - c.translation).squaredNorm() <= s2;
    });
    if (!near) kept.push_back(c);
  }
}

}  // namespace snapfit
