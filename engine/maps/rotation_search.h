#pragma once
// Exhaustive pose search by FFT (seed 000 Fig. 1c; the docking codes' scheme): one full
// translational map per rotation of an SO(3) grid (core/so3_grid.h), its best minima
// kept (engine/maps/map_minima.h), all rotations' candidates merged into the best poses.
#include <Eigen/Geometry>
#include <cstddef>
#include <functional>
#include <vector>

#include "engine/maps/full_map.h"
#include "snapfit/pose.h"

namespace snapfit {

struct PoseCandidate {
  Pose pose;                 // part 2 relative to part 1
  double energy = 0;         // E(R, t) of the map
  std::size_t rotation = 0;  // index into the rotations searched
  std::size_t cell = 0;      // grid index of t in the map
};

struct ScanOptions {
  std::size_t minima_per_rotation = 4;  // best minima kept per map
  double separation = 0;                // their least distance apart (scene units)
};

struct RotationScan {
  std::vector<PoseCandidate> candidates;
  std::vector<std::size_t> rotations;  // the rotation indices mapped, in order
  std::vector<double> best_energy;     // per mapped rotation: its map's lowest finite E (NaN: none)
};

// Maps rotations[i] for every i in `indices`, in that order, in batches of
// mapper.batch() rotations, two batches in flight (the next computes on the device while
// the host reads one). `done` runs after each map. The candidates do not depend on the
// batch size.
RotationScan scan_rotations(TranslationMapper& mapper, const std::vector<Eigen::Quaterniond>& rotations,
                            const std::vector<std::size_t>& indices, const ScanOptions& options,
                            const std::function<void()>& done = {});

// Candidates best first (ties: lower rotation index, then lower grid index, so the
// order does not depend on who mapped what), those within `distance` and `angle_rad` of
// a better kept one dropped, at most `top`.
std::vector<PoseCandidate> merge_candidates(std::vector<PoseCandidate> candidates, std::size_t top, double distance,
                                            double angle_rad);

}  // namespace snapfit
