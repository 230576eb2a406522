#include "engine/maps/rotation_search.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/so3_grid.h"
#include "engine/maps/map_minima.h"

namespace snapfit {

RotationScan scan_rotations(TranslationMapper& mapper, const std::vector<Eigen::Quaterniond>& rotations,
                            const std::vector<std::size_t>& indices, const ScanOptions& options,
                            const std::function<void()>& done) {
  RotationScan scan;
  MapMinimaResult map;
  std::vector<float> energy;
  // On a device FFT the device finds each map's minima and only they are read back;
  // otherwise the host finds them in the map, after queueing the next batch.
  const bool on_device = mapper.minima_on_device();
  const MapOutput output = on_device ? MapOutput::minima : MapOutput::energy;
  const std::size_t n = indices.size(), batch = mapper.batch(), slots = TranslationMapper::slots;
  const std::size_t batches = (n + batch - 1) / batch;
  std::vector<Eigen::Matrix3d> R(batch);
  // Batch b holds indices [b batch, min((b + 1) batch, n)) and goes to slot b % slots.
  auto submit = [&](std::size_t b) {
    const std::size_t first = b * batch, count = std::min(batch, n - first);
    for (std::size_t m = 0; m < count; ++m) R[m] = rotations[indices[first + m]].toRotationMatrix();
    mapper.submit(int(b % slots), R.data(), count, output);
  };
  auto keep = [&](std::size_t r) {
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
  };
  for (std::size_t b = 0; b < batches && b < slots; ++b) submit(b);
  for (std::size_t b = 0; b < batches; ++b) {
    const int slot = int(b % slots);
    const std::size_t first = b * batch, count = std::min(batch, n - first);
    for (std::size_t m = 0; m < count; ++m) {
      if (on_device) {
        mapper.collect_minima(slot, options.minima_per_rotation, options.separation, map, m);
      } else {
        mapper.collect(slot, energy, m);
        // The batch's last map is in `energy` and the slot is free: queue the batch
        // after next before finding the minima on the host.
        if (m + 1 == count && b + slots < batches) submit(b + slots);
        map_minima(mapper.grid(), energy, options.minima_per_rotation, options.separation, map);
      }
      keep(indices[first + m]);
    }
    if (on_device && b + slots < batches) submit(b + slots);
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
