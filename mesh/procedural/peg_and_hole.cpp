// The peg and the hole block it fits (procedural_parts.h). Both are built from the
// same regular N-gon (unit_ngon), so at clearance 0 the peg's side walls and the
// hole's walls coincide exactly, and at clearance c their parallel faces are c apart.
#include <cmath>

#include "mesh/procedural/procedural_internal.h"

namespace snapfit::procedural {

namespace {

// Where the ray from the origin along `dir` leaves the square [-s, s]^2. For the
// diagonal directions of unit_ngon (|x| == |y| exactly) this is exactly the corner.
Eigen::Vector2d square_boundary(const Eigen::Vector2d& dir, double s) {
  const double ax = std::abs(dir.x()), ay = std::abs(dir.y());
  if (ax >= ay) return {std::copysign(s, dir.x()), s * dir.y() / ax};
  return {s * dir.x() / ay, std::copysign(s, dir.y())};
}

}  // namespace

// Prism over the N-gon along +z, z in [0, length]; the bottom edge optionally
// bevelled at 45 degrees (circumradius radius - chamfer at z = 0, radius from z = chamfer).
Mesh make_peg(const PegParams& p) {
  const auto ngon = unit_ngon(p.segments);
  const Eigen::Vector2d axis(0, 0);
  MeshBuilder b;
  const std::vector<int> top = b.ring(ngon, axis, p.radius, p.length);
  std::vector<int> bottom;
  if (p.chamfer > 0) {
    bottom = b.ring(ngon, axis, p.radius - p.chamfer, 0.0);
    const std::vector<int> shoulder = b.ring(ngon, axis, p.radius, p.chamfer);
    b.stitch(bottom, shoulder);  // bevel, normals outward and down
    b.stitch(shoulder, top);     // side wall
  } else {
    bottom = b.ring(ngon, axis, p.radius, 0.0);
    b.stitch(bottom, top);
  }
  b.fan(b.vertex({0, 0, 0}), bottom, /*up=*/false);
  b.fan(b.vertex({0, 0, p.length}), top, /*up=*/true);
  return std::move(b.mesh);
}

// Box [-w/2, w/2]^2 x [-height, 0] minus an N-gon hole down -z from z = 0.
// The top face (square with the hole) is made of the convex quads between the hole's
// entry ring and the points where the rays through its vertices leave the square;
// the box sides and the bottom use the same boundary points, so everything conforms.
Mesh make_hole_block(const HoleBlockParams& p) {
  const int n = p.segments;
  const auto ngon = unit_ngon(n);
  const Eigen::Vector2d axis(0, 0);
  const double half = 0.5 * p.width;
  const double radius = p.hole_radius();
  MeshBuilder b;

  // Square boundary rings at the top (z = 0) and the bottom (z = -height).
  std::vector<int> sq_top(n), sq_bottom(n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d q = square_boundary(ngon[i], half);
    sq_top[i] = b.vertex({q.x(), q.y(), 0.0});
    sq_bottom[i] = b.vertex({q.x(), q.y(), -p.height});
  }
  // Hole rings: entry (countersunk to radius + chamfer), end of the countersink, bottom.
  const std::vector<int> entry = b.ring(ngon, axis, radius + p.chamfer, 0.0);
  const std::vector<int> wall_top = p.chamfer > 0 ? b.ring(ngon, axis, radius, -p.chamfer) : entry;
  const std::vector<int> wall_bottom = b.ring(ngon, axis, radius, -p.hole_depth);

  b.stitch(sq_top, entry);                       // top face, normal +z
  b.stitch(sq_bottom, sq_top);                   // box sides, normals outward
  if (p.chamfer > 0) b.stitch(entry, wall_top);  // countersink, normals up and toward the axis
  b.stitch(wall_top, wall_bottom);               // hole wall, normals toward the axis
  if (p.through()) {
    b.stitch(wall_bottom, sq_bottom);  // bottom face with the hole's exit, normal -z
  } else {
    b.fan(b.vertex({0, 0, -p.hole_depth}), wall_bottom, /*up=*/true);  // flat hole bottom
    b.fan(b.vertex({0, 0, -p.height}), sq_bottom, /*up=*/false);       // box bottom
  }
  return std::move(b.mesh);
}

}  // namespace snapfit::procedural
