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
  MapMinimaResult map;
  std::vector<float> energy;
  // On clFFT the device finds each map's minima and only they are read back; otherwise
  // the host finds them in the map, after queueing the next one.
  const bool on_device = mapper.minima_on_device();
  const MapOutput output = on_device ? MapOutput::minima : MapOutput::energy;
  const std::size_t n = indices.size();
  for (std::size_t i = 0; i < n && i < std::size_t(TranslationMapper::slots); ++i)
    mapper.submit(int(i % TranslationMapper::slots), rotations[indices[i]].toRotationMatrix(), output);
  for (std::size_t i = 0; i < n; ++i) {
    const int slot = int(i % TranslationMapper::slots);
    if (on_device)
      mapper.collect_minima(slot, options.minima_per_rotation, options.separation, map);
    else
      mapper.collect(slot, energy);
    // The slot is free again: queue the map after next before using this one.
    if (i + TranslationMapper::slots < n)
      mapper.submit(slot, rotations[indices[i + TranslationMapper::slots]].toRotationMatrix(), output);
    if (!on_device) map_minima(mapper.grid(), energy, options.minima_per_rotation, options.separation, map);
    const std::size_t r = indices[i];
    scan.rotations.push_back(r);
    scan.best_energy.push_back(map.best);
    for (const MapMinimum& m : map.minima) {
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
