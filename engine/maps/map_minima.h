#pragma once
// The best fits of one translational map: local minima of E(R, t) over the grid's
// translations, thinned by non-maximum suppression (a minimum is kept only when no
// better kept one lies within `separation` of it), best first.
#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <vector>

#include "core/grid.h"

namespace snapfit {

struct MapMinimum {
  std::size_t index = 0;  // grid index
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();
  float energy = 0;
};

// Minima with E < 0 (contact that fits; E = 0 is no contact) that are <= each of their
// 26 neighbours (NaN neighbours and those beyond the grid do not count; on a plateau the
// lowest grid index counts), at most `count`, each farther than `separation` from every
// better one kept. Ties in energy go to the lower grid index, so the result is deterministic.
std::vector<MapMinimum> map_minima(const GridSpec& grid, const std::vector<float>& energy, std::size_t count,
                                   double separation);

// One map's minima and its lowest value.
struct MapMinimaResult {
  std::vector<MapMinimum> minima;                        // as map_minima gives them
  float best = std::numeric_limits<float>::quiet_NaN();  // the lowest finite E (NaN: none)
};

// map_minima into out.minima, and the lowest finite E of `energy` into out.best.
void map_minima(const GridSpec& grid, const std::vector<float>& energy, std::size_t count, double separation,
                MapMinimaResult& out);

// map_minima's last step on minima found elsewhere (engine/maps/device_minima.h): sorts
// `candidates` (the minima with E < 0, in any order) best first, ties to the lower grid
// index, then writes into `kept` at most `count` of them, each farther than `separation`
// from every better one kept. Allocates nothing when `kept` has the capacity.
void thin_minima(std::vector<MapMinimum>& candidates, std::size_t count, double separation,
                 std::vector<MapMinimum>& kept);

}  // namespace snapfit
