#include "engine/rotation_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/so3_grid.h"
#include "engine/map_minima.h"

namespace snapfit {

RotationScan scan_rotations(TranslationMapper& mapper, const std::vector<Eigen::Quaterniond>& rotations,
                            const std::vector<std::size_t>& indices, const ScanOptions& options,
                            const std::function<void()>& done) {
  RotationScan scan;
  std::vector<float> energy;
  const std::size_t n = indices.size();
  for (std::size_t i = 0; i < n && i < std::size_t(TranslationMapper::slots); ++i)
    mapper.submit(int(i % TranslationMapper::slots), rotations[indices[i]].toRotationMatrix());
  for (std::size_t i = 0; i < n; ++i) {
    const int slot = int(i % TranslationMapper::slots);
    mapper.collect(slot, energy);
    // The slot is free again: queue the map after next before reading this one.
    if (i + TranslationMapper::slots < n)
      mapper.submit(slot, rotations[indices[i + TranslationMapper::slots]].toRotationMatrix());
    const std::size_t r = indices[i];
    double best = std::numeric_limits<double>::quiet_NaN();
    for (float e : energy)
      if (std::isfinite(e) && !(e >= best)) best = e;
    scan.rotations.push_back(r);
    scan.best_energy.push_back(best);
    for (const MapMinimum& m : map_minima(mapper.grid(), energy, options.minima_per_rotation, options.separation)) {
      PoseCandidate c;
      c.pose.rotation = rotations[r];
      c.pose.translation = m.translation;
      c.energy = m.energy;
      c.rotation = r;
      c.cell = m.index;
      scan.candidates.push_back(c);
    }
    if (done) done();
  }
  return scan;
}

std::vector<PoseCandidate> merge_candidates(std::vector<PoseCandidate> candidates, std::size_t top, double distance,
                                            double angle_rad) {
  std::sort(candidates.begin(), candidates.end(), [](const PoseCandidate& a, const PoseCandidate& b) {
    if (a.energy != b.energy) return a.energy < b.energy;
    if (a.rotation != b.rotation) return a.rotation < b.rotation;
    return a.cell < b.cell;
  });
  std::vector<PoseCandidate> kept;
  for (const PoseCandidate& c : candidates) {
    if (kept.size() >= top) break;
    const bool near = std::any_of(kept.begin(), kept.end(), [&](const PoseCandidate& k) {
      return (k.pose.translation - c.pose.translation).norm() <= distance &&
             rotation_distance(k.pose.rotation, c.pose.rotation) <= angle_rad;
    });
    if (!near) kept.push_back(c);
  }
  return kept;
}

}  // namespace snapfit
