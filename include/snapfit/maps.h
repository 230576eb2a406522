#pragma once
// The energy for every translation of part 2 at one rotation (a C-space slice,
// Behandish & Ilies 2016 Fig. 5 bottom row; docs/design.md "Correlation in the Fourier
// domain"): the pointwise product of both parts' spectra and one inverse FFT, on the
// assembly's device.
//
//   snapfit::Assembly assembly(snapfit::load_scene("scenes/default.json"));
//   snapfit::TranslationMap map = snapfit::translational_energy_map(assembly, {});
//   // map.energy[map.grid.index(i, j, k)]: E at translation map.grid.point(i, j, k)
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "snapfit/grid.h"

namespace snapfit {

class Assembly;

struct TranslationMapRequest {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // part 2's, in part 1's frame
  std::size_t modes = 0;  // 0 keeps every mode; otherwise the low-pass ball holding about that many
};

struct TranslationMap {
  GridSpec grid;              // translations t of part 2 (part 1's frame), regular order
  std::vector<float> energy;  // E(R, t) = -Re f; NaN where the periodic sum would alias
  double seconds = 0;
};

// The map with tricubic interpolation of part 2's rotated spectrum. Throws
// snapfit::Error naming the device when a buffer, kernel or FFT plan fails.
TranslationMap translational_energy_map(const Assembly& assembly, const TranslationMapRequest& request);

}  // namespace snapfit
