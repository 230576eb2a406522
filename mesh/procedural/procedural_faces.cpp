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

namespace {

// The fillet at a peg's foot: the quarter circle of three_peg_pair.cpp, from the wall's
// foot (z = f, on the cylinder) to the flat face (z = 0, at r + f), about (z, rho) = (f, r + f).
AnalyticFace fillet(const char* name, const Eigen::Vector3d& centre, double r, double f) {
  AnalyticFace t;
  t.kind = FaceKind::torus;
  t.name = name;
  t.origin = centre;
  t.axis = Eigen::Vector3d::UnitZ();
  t.a0 = f, t.r0 = r;
  t.a1 = 0, t.r1 = r + f;
  t.ac = f, t.rc = r + f;
  return t;
}

// The faces the base and the cover share along the mating surface, with the normals of
// the base (`base`) or the cover: the flat face z = 0 less the three fillets' discs, and
// per peg its wall, its top (the cover's hole ceiling) and its fillet; then the outer box
// (sides and the bottom at -base_thickness, or the top at top()).
std::vector<AnalyticFace> three_peg_faces(const ThreePegParams& p, bool base) {
  const double sign = base ? 1.0 : -1.0;  // the base's mating normals point up
  const Eigen::Vector3d up = Eigen::Vector3d::UnitZ();
  const double hx = 1.5 * p.cell, hy = p.cell;
  const double z0 = base ? -p.base_thickness : 0.0, z1 = base ? 0.0 : p.top();
  std::vector<AnalyticFace> faces;
  AnalyticFace flat = plane(base ? "base flat" : "cover flat", Eigen::Vector3d::Zero(), sign * up);
  flat.lo = Eigen::Vector3d(-hx, -hy, 0);
  flat.hi = Eigen::Vector3d(hx, hy, 0);
  static const char* const kWall[2][3] = {{"cover hole 1", "cover hole 2", "cover hole 3"},
                                          {"base peg 1", "base peg 2", "base peg 3"}};
  static const char* const kTop[2][3] = {{"cover ceiling 1", "cover ceiling 2", "cover ceiling 3"},
                                         {"base peg top 1", "base peg top 2", "base peg top 3"}};
  static const char* const kFillet[2] = {"cover fillet", "base fillet"};
  std::vector<AnalyticFace> pegs;
  for (int k = 0; k < 3; ++k) {
    const double r = mean_radius(p.peg_radii[k], p.segments), h = p.peg_heights[k], f = p.fillet_radii[k];
    const Eigen::Vector3d centre((kPegCells[k][0] - 1) * p.cell, (kPegCells[k][1] - 0.5) * p.cell, 0);
    flat.holes.push_back({centre, r + f});
    AnalyticFace wall = revolution(kWall[base][k], f, r, h, r, base);
    wall.origin = centre;
    pegs.push_back(wall);
    AnalyticFace top = plane(kTop[base][k], centre + h * up, sign * up);
    top.r_out = r;
    pegs.push_back(top);
    if (f > 0) pegs.push_back(fillet(kFillet[base], centre, r, f));
  }
  faces.push_back(flat);
  faces.insert(faces.end(), pegs.begin(), pegs.end());
  const Eigen::Vector3d lo(-hx, -hy, z0), hi(hx, hy, z1);
  auto boxed = [&](AnalyticFace f) {
    f.lo = lo;
    f.hi = hi;
    return f;
  };
  faces.push_back(boxed(plane("side +x", Eigen::Vector3d(hx, 0, 0), Eigen::Vector3d::UnitX())));
  faces.push_back(boxed(plane("side -x", Eigen::Vector3d(-hx, 0, 0), -Eigen::Vector3d::UnitX())));
  faces.push_back(boxed(plane("side +y", Eigen::Vector3d(0, hy, 0), Eigen::Vector3d::UnitY())));
  faces.push_back(boxed(plane("side -y", Eigen::Vector3d(0, -hy, 0), -Eigen::Vector3d::UnitY())));
  faces.push_back(base ? boxed(plane("base bottom", Eigen::Vector3d(0, 0, z0), -up))
                       : boxed(plane("cover top", Eigen::Vector3d(0, 0, z1), up)));
  return faces;
}

}  // namespace

// The base: the flat mating face, each peg's wall, top and fillet, the sides and bottom.
std::vector<AnalyticFace> three_peg_base_faces(const ThreePegParams& p) { return three_peg_faces(p, true); }

// The cover: the same mating faces with the normals reversed (each peg's wall a hole,
// its top the hole's ceiling, its fillet the hole's rounded entry), the sides and top.
std::vector<AnalyticFace> three_peg_cover_faces(const ThreePegParams& p) { return three_peg_faces(p, false); }

}  // namespace snapfit::procedural
