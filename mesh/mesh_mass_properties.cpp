#include "mesh/mesh_mass_properties.h"

#include <Eigen/Geometry>
#include <cmath>

#include "snapfit/error.h"

namespace snapfit {

SolidMoments solid_moments(const Mesh& mesh, const Eigen::Vector3d& origin) {
  if (mesh.empty()) throw Error("solid moments: the mesh has no triangles");
  double six_volume = 0, sixty_r2 = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]] - origin, b = mesh.vertices[t[1]] - origin,
                          c = mesh.vertices[t[2]] - origin;
    const double a_dot_n = a.dot((b - a).cross(c - a));  // (q.n) 2A, constant on the face
    six_volume += a_dot_n;
    sixty_r2 += a_dot_n * (a.squaredNorm() + b.squaredNorm() + c.squaredNorm() + a.dot(b) + b.dot(c) + c.dot(a));
  }
  SolidMoments m;
  m.volume = six_volume / 6.0;
  if (!(std::abs(m.volume) > 0) || !std::isfinite(m.volume)) throw Error("solid moments: the mesh encloses no volume");
  m.mean_square_radius = (sixty_r2 / 60.0) / m.volume;
  return m;
}

}  // namespace snapfit
