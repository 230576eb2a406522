#include "mesh/mesh_slice.h"

#include <string>

#include "snapfit/error.h"

namespace snapfit {

std::vector<OutlineSegment> mesh_slice_outline(const Mesh& mesh, char axis, double value) {
  if (axis != 'x' && axis != 'y' && axis != 'z')
    throw Error("mesh_slice_outline: axis must be 'x', 'y' or 'z', not '" + std::string(1, axis) + "'");
  const int a = axis - 'x';
  const int u = a == 0 ? 1 : 0, v = a == 2 ? 1 : 2;
  std::vector<OutlineSegment> out;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    Eigen::Vector3d p[3];
    double d[3];
    int above = 0;
    for (int k = 0; k < 3; ++k) {
      p[k] = mesh.vertices[t[k]];
      d[k] = p[k][a] - value;
      above += d[k] >= 0;
    }
    if (above == 0 || above == 3) continue;
    // The two edges whose ends lie on opposite sides: d_i >= 0 > d_j, so d_i - d_j > 0.
    Eigen::Vector2d ends[2];
    int found = 0;
    for (int k = 0; k < 3 && found < 2; ++k) {
      const int i = k, j = (k + 1) % 3;
      if ((d[i] >= 0) == (d[j] >= 0)) continue;
      const double s = d[i] / (d[i] - d[j]);
      const Eigen::Vector3d q = p[i] + s * (p[j] - p[i]);
      ends[found++] = {q[u], q[v]};
    }
    out.push_back({ends[0], ends[1]});
  }
  return out;
}

}  // namespace snapfit
