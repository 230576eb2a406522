// The analytic faces of the peg and the hole block (procedural_parts.h): the planes,
// cylinders and cones their meshes tessellate, in the same frames as make_peg and
// make_hole_block. The meshes are regular N-gons, whose facets lie between the apothem
// R cos(pi/N) and the circumradius R from the axis; a cylinder or cone takes the mean of
// the two as its radius, so no facet point lies farther than R (1 - cos(pi/N)) / 2 from it
// and the peg's and the hole's radii differ by the clearance (to O(1/N^2)).
#include <cmath>

#include "mesh/procedural/procedural_internal.h"

namespace snapfit::procedural {

namespace {

double mean_radius(double circumradius, int segments) {
  return 0.5 * circumradius * (1.0 + std::cos(kPi / segments));
}

AnalyticFace plane(const char* name, const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
  AnalyticFace f;
  f.kind = FaceKind::plane;
  f.name = name;
  f.origin = origin;
  f.axis = normal;
  return f;
}

AnalyticFace revolution(const char* name, double a0, double r0, double a1, double r1, bool material_inside) {
  AnalyticFace f;
  f.kind = r0 == r1 ? FaceKind::cylinder : FaceKind::cone;
  f.name = name;
  f.origin = Eigen::Vector3d::Zero();
  f.axis = Eigen::Vector3d::UnitZ();
  f.a0 = a0;
  f.r0 = r0;
  f.a1 = a1;
  f.r1 = r1;
  f.material_inside = material_inside;
  return f;
}

}  // namespace

// Bottom disc (z = 0), the 45-degree chamfer cone, the side cylinder, the top disc (z = length).
std::vector<AnalyticFace> peg_faces(const PegParams& p) {
  const double r = mean_radius(p.radius, p.segments);
  const double rb = mean_radius(p.radius - p.chamfer, p.segments);
  std::vector<AnalyticFace> faces;
  AnalyticFace bottom = plane("peg bottom", Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ());
  bottom.r_out = rb;
  faces.push_back(bottom);
  if (p.chamfer > 0) faces.push_back(revolution("peg chamfer", 0.0, rb, p.chamfer, r, true));
  faces.push_back(revolution("peg side", p.chamfer, r, p.length, r, true));
  AnalyticFace top = plane("peg top", Eigen::Vector3d(0, 0, p.length), Eigen::Vector3d::UnitZ());
  top.r_out = r;
  faces.push_back(top);
  return faces;
}

// Top face (z = 0, the square less the entry), the four box sides, the box bottom (less
// the exit of a through hole), the countersink cone, the hole wall, the hole's floor.
std::vector<AnalyticFace> hole_block_faces(const HoleBlockParams& p) {
  const double half = 0.5 * p.width;
  const double r = mean_radius(p.hole_radius(), p.segments);
  const double entry = mean_radius(p.hole_radius() + p.chamfer, p.segments);
  const Eigen::Vector3d lo(-half, -half, -p.height), hi(half, half, 0.0);
  std::vector<AnalyticFace> faces;
  auto boxed = [&](AnalyticFace f) {
    f.lo = lo;
    f.hi = hi;
    return f;
  };
  AnalyticFace top = boxed(plane("block top", Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ()));
  top.r_in = entry;
  faces.push_back(top);
  faces.push_back(boxed(plane("block side +x", Eigen::Vector3d(half, 0, 0), Eigen::Vector3d::UnitX())));
  faces.push_back(boxed(plane("block side -x", Eigen::Vector3d(-half, 0, 0), -Eigen::Vector3d::UnitX())));
  faces.push_back(boxed(plane("block side +y", Eigen::Vector3d(0, half, 0), Eigen::Vector3d::UnitY())));
  faces.push_back(boxed(plane("block side -y", Eigen::Vector3d(0, -half, 0), -Eigen::Vector3d::UnitY())));
  AnalyticFace bottom = boxed(plane("block bottom", Eigen::Vector3d(0, 0, -p.height), -Eigen::Vector3d::UnitZ()));
  if (p.through()) bottom.r_in = r;
  faces.push_back(bottom);
  if (p.chamfer > 0) faces.push_back(revolution("hole chamfer", -p.chamfer, r, 0.0, entry, false));
  faces.push_back(revolution("hole wall", -p.hole_depth, r, -p.chamfer, r, false));
  if (!p.through()) {
    // The floor's normal points out of the material: up, into the hole.
    AnalyticFace floor = plane("hole floor", Eigen::Vector3d(0, 0, -p.hole_depth), Eigen::Vector3d::UnitZ());
    floor.r_out = r;
    faces.push_back(floor);
  }
  return faces;
}

}  // namespace snapfit::procedural
