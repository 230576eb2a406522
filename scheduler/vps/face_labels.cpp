#include "scheduler/vps/face_labels.h"

namespace snapfit {

std::vector<std::int16_t> label_voxmap(const Voxmap& map, const std::vector<AnalyticFace>& faces) {
  std::vector<std::int16_t> out(map.state.size(), kNoFace);
  const double s = map.voxel_size;
  for (int k = 0; k < map.dims.z(); ++k)
    for (int j = 0; j < map.dims.y(); ++j)
      for (int i = 0; i < map.dims.x(); ++i) {
        const std::size_t id = map.index(i, j, k);
        if (map.state[id] != VoxelState::surface) continue;
        out[id] = face_at(faces, map.centre(i, j, k), s, 0.5 * s);
      }
  return out;
}

std::vector<std::int16_t> label_point_shell(const PointShell& shell, const std::vector<AnalyticFace>& faces) {
  std::vector<std::int16_t> out(shell.points.size(), kNoFace);
  for (std::size_t i = 0; i < shell.points.size(); ++i)
    out[i] = face_at(faces, shell.points[i], shell.spacing, 0.5 * shell.spacing);
  return out;
}

}  // namespace snapfit
