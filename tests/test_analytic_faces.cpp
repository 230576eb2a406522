// Analytic faces of the procedural parts (mesh/analytic_faces.h, procedural_parts.h):
// every shell point of a chamfered peg maps to the face its position says, or to an edge
// within the edge band of a profile corner; every surface voxel of a hole block maps to a
// face, the wall's voxels to the wall; radii differ by the clearance; the three-peg pair's
// planes, cylinders and fillets; excluded discs, turned faces; bad input.
#include <Eigen/Geometry>
#include <cmath>
#include <cstring>
#include <doctest/doctest.h>

#include "mesh/analytic_faces.h"
#include "mesh/procedural/procedural_parts.h"
#include "scheduler/vps/face_labels.h"
#include "scheduler/vps/voxmap.h"
#include "snapfit/error.h"

using namespace snapfit;

namespace {

int find_face(const std::vector<AnalyticFace>& faces, const char* name) {
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (std::strcmp(faces[i].name, name) == 0) return static_cast<int>(i);
  return -100;
}

}  // namespace

TEST_CASE("analytic faces: every shell point of a chamfered peg maps to its face or, near a corner, to an edge") {
  const double R = 5, L = 20, c = 1, s = 0.5;
  const ProceduralPartSpec spec{"peg", {{"radius", R}, {"length", L}, {"chamfer", c}}, {}};
  const std::vector<AnalyticFace> faces = procedural_part_faces(spec);
  REQUIRE(faces.size() == 4);
  const int bottom = find_face(faces, "peg bottom"), chamfer = find_face(faces, "peg chamfer"),
            side = find_face(faces, "peg side"), top = find_face(faces, "peg top");
  CHECK(faces[side].kind == FaceKind::cylinder);
  CHECK(faces[chamfer].kind == FaceKind::cone);
  CHECK(faces[top].kind == FaceKind::plane);
  CHECK(faces[side].material_inside);

  const PointShell shell = build_point_shell(make_procedural_part(spec), s);
  const std::vector<std::int16_t> labels = label_point_shell(shell, faces);
  REQUIRE(labels.size() == shell.points.size());
  // The profile's corners in (z, radius), at the 64-gon's mean radius; a facet point lies
  // within R (1 - cos(pi/64)) / 2 < 0.004 of it, so the test allows a slack of 0.01.
  const double m = 0.5 * (1 + std::cos(M_PI / 64));
  const Eigen::Vector2d corners[3] = {{0, (R - c) * m}, {c, R * m}, {L, R * m}};
  const double band = 0.5 * s, slack = 0.01;
  int edges = 0, on_face = 0;
  for (std::size_t i = 0; i < shell.points.size(); ++i) {
    const Eigen::Vector3d& p = shell.points[i];
    const Eigen::Vector2d q(p.z(), std::hypot(p.x(), p.y()));
    const int expected = p.z() < 1e-9 ? bottom : p.z() > L - 1e-9 ? top : p.z() < c ? chamfer : side;
    double corner = 1e9;
    for (const Eigen::Vector2d& k : corners) corner = std::min(corner, (q - k).norm());
    CAPTURE(p.transpose());
    CAPTURE(corner);
    CHECK(labels[i] != kNoFace);
    if (corner < band - slack) {
      CHECK(labels[i] == kEdge);
      ++edges;
    } else if (corner > band + slack) {
      CHECK(labels[i] == expected);
      ++on_face;
    } else {
      CHECK((labels[i] == kEdge || labels[i] == expected));
    }
  }
  CHECK(edges > 0);
  CHECK(on_face > 0.8 * shell.points.size());
}

TEST_CASE("analytic faces: every surface voxel of a hole block maps to a face, the wall's to the wall") {
  const double s = 0.5, depth = 15, c = 1, clearance = 0.5;
  const ProceduralPartSpec spec{"hole_block",
                                {{"peg_radius", 5},
                                 {"clearance", clearance},
                                 {"hole_depth", depth},
                                 {"width", 20},
                                 {"height", 20},
                                 {"chamfer", c}},
                                {}};
  const std::vector<AnalyticFace> faces = procedural_part_faces(spec);
  REQUIRE(faces.size() == 9);  // top, 4 sides, bottom, countersink, wall, floor
  const int wall = find_face(faces, "hole wall");
  REQUIRE(wall >= 0);
  CHECK(faces[wall].kind == FaceKind::cylinder);
  CHECK_FALSE(faces[wall].material_inside);
  const double r = faces[wall].radius();

  const Voxmap map = build_voxmap(make_procedural_part(spec), s, 2);
  const std::vector<std::int16_t> labels = label_voxmap(map, faces);
  REQUIRE(labels.size() == map.state.size());
  std::vector<int> per_face(faces.size(), 0);
  int edges = 0;
  for (int k = 0; k < map.dims.z(); ++k)
    for (int j = 0; j < map.dims.y(); ++j)
      for (int i = 0; i < map.dims.x(); ++i) {
        const std::size_t id = map.index(i, j, k);
        const std::int16_t label = labels[id];
        if (map.state[id] != VoxelState::surface) {
          CHECK(label == kNoFace);
          continue;
        }
        const Eigen::Vector3d x = map.centre(i, j, k);
        const double rho = std::hypot(x.x(), x.y());
        CAPTURE(x.transpose());
        CHECK(label != kNoFace);  // a surface voxel's centre lies within sqrt(3)/2 voxel of the mesh
        if (label == kEdge) ++edges;
        if (label >= 0) ++per_face[label];
        // Near the wall and farther than a voxel from its ends: the wall.
        const bool in_wall_band = rho < r + 0.9 * s && x.z() > -depth + 1.5 * s && x.z() < -c - 1.5 * s;
        if (in_wall_band) CHECK(label == wall);
        if (label == wall) {
          CHECK(std::abs(rho - r) <= s);
          CHECK(x.z() >= -depth - s);
          CHECK(x.z() <= -c + s);
        }
      }
  for (std::size_t f = 0; f < faces.size(); ++f) {
    CAPTURE(faces[f].name);
    CHECK(per_face[f] > 0);
  }
  CHECK(edges > 0);

  // The peg that fits it: the radii differ by the clearance (to O(1/N^2)).
  const std::vector<AnalyticFace> peg = procedural_part_faces({"peg", {{"radius", 5}, {"length", 20}}, {}});
  CHECK(r - peg[find_face(peg, "peg side")].radius() == doctest::Approx(clearance).epsilon(1e-3));
}

TEST_CASE("analytic faces: the three-peg pair's planes and cylinders label its points, its fillets' stay unlabelled") {
  // Pegs at the cell centres (-20, -10), (0, 10), (20, -10) (procedural_parts.h), radii
  // 3, 4.5, 6, heights 8, 10, 12, fillets 1, 1.5, 2 (scenes/three_pegs.json).
  const double cell = 20, s = 0.5;
  const double radii[3] = {3, 4.5, 6}, heights[3] = {8, 10, 12}, fillets[3] = {1, 1.5, 2};
  const Eigen::Vector2d centres[3] = {{-20, -10}, {0, 10}, {20, -10}};
  ProceduralPartSpec spec{"three_peg_cover",
                          {{"cell", cell}, {"base_thickness", 8}, {"cover_thickness", 6}},
                          {{"peg_radii", {3, 4.5, 6}}, {"peg_heights", {8, 10, 12}}, {"fillet_radii", {1, 1.5, 2}}}};
  const std::vector<AnalyticFace> cover = procedural_part_faces(spec);
  REQUIRE(cover.size() == 1 + 3 * 3 + 5);  // flat, 3 x (hole, ceiling, fillet), 4 sides, top
  const int flat = find_face(cover, "cover flat");
  REQUIRE(flat >= 0);
  CHECK(cover[flat].axis.isApprox(-Eigen::Vector3d::UnitZ()));  // out of the cover's material
  REQUIRE(cover[flat].holes.size() == 3);
  const char* holes[3] = {"cover hole 1", "cover hole 2", "cover hole 3"};
  const char* ceilings[3] = {"cover ceiling 1", "cover ceiling 2", "cover ceiling 3"};
  for (int k = 0; k < 3; ++k) {
    const int hole = find_face(cover, holes[k]);
    REQUIRE(hole >= 0);
    CHECK(cover[hole].kind == FaceKind::cylinder);
    CHECK_FALSE(cover[hole].material_inside);
    CHECK(cover[hole].radius() == doctest::Approx(radii[k]).epsilon(1e-3));
    CHECK(cover[flat].holes[k].radius == doctest::Approx(radii[k] + fillets[k]).epsilon(1e-3));
  }

  // Every shell point of the cover by where it lies (an independent classification from
  // the parameters): on the flat face a voxel away from every fillet, the flat face; on a
  // hole's wall a voxel from its ends, that hole; on a ceiling inside r - s, the ceiling;
  // on a fillet's arc farther than the band from its ends, no face.
  const Mesh mesh = make_procedural_part(spec);
  const PointShell shell = build_point_shell(mesh, s);
  const std::vector<std::int16_t> labels = label_point_shell(shell, cover);
  int on_flat = 0, on_wall = 0, on_fillet = 0;
  for (std::size_t i = 0; i < shell.points.size(); ++i) {
    const Eigen::Vector3d& x = shell.points[i];
    CAPTURE(x.transpose());
    const bool inside_footprint = std::abs(x.x()) < 1.5 * cell - s && std::abs(x.y()) < cell - s;
    for (int k = 0; k < 3; ++k) {
      const double rho = (x.head<2>() - centres[k]).norm(), r = radii[k], f = fillets[k], h = heights[k];
      if (std::abs(x.z()) < 1e-6 && rho > r + f + s && inside_footprint) {
        bool far = true;
        for (int m = 0; m < 3; ++m) far &= (x.head<2>() - centres[m]).norm() > radii[m] + fillets[m] + s;
        if (far && k == 0) {
          CHECK(labels[i] == flat);
          ++on_flat;
        }
      }
      if (std::abs(rho - r) < 0.05 && x.z() > f + s && x.z() < h - s) {
        CHECK(labels[i] == find_face(cover, holes[k]));
        ++on_wall;
      }
      if (std::abs(x.z() - h) < 1e-6 && rho < r - s) CHECK(labels[i] == find_face(cover, ceilings[k]));
      // On the fillet: distance f from the arc's centre (rho, z) = (r + f, f), between its ends.
      const Eigen::Vector2d q(rho - (r + f), x.z() - f);
      if (std::abs(q.norm() - f) < 0.05 && q.x() < 0 && q.y() < 0 &&
          (Eigen::Vector2d(rho, x.z()) - Eigen::Vector2d(r, f)).norm() > s &&
          (Eigen::Vector2d(rho, x.z()) - Eigen::Vector2d(r + f, 0)).norm() > s) {
        CHECK(labels[i] == kNoFace);
        ++on_fillet;
      }
    }
  }
  CHECK(on_flat > 100);
  CHECK(on_wall > 100);
  CHECK(on_fillet > 10);

  // The base has the same faces with its own normals: pegs, tops up, the flat face up.
  spec.type = "three_peg_base";
  const std::vector<AnalyticFace> base = procedural_part_faces(spec);
  REQUIRE(base.size() == cover.size());
  CHECK(base[find_face(base, "base flat")].axis.isApprox(Eigen::Vector3d::UnitZ()));
  CHECK(base[find_face(base, "base peg 3")].material_inside);
  CHECK(base[find_face(base, "base peg top 3")].origin.isApprox(Eigen::Vector3d(20, -10, 12)));
  // The torus's distance against its closed form: from the arc's centre, f; from a point
  // beyond the arc's end on the flat side, the distance to that end.
  const AnalyticFace& fillet = base[find_face(base, "base peg 3") + 2];
  REQUIRE(fillet.kind == FaceKind::torus);
  const double r3 = base[find_face(base, "base peg 3")].radius();
  CHECK(face_distance(fillet, Eigen::Vector3d(20 + r3 + 2, -10, 2)) == doctest::Approx(2));
  CHECK(face_distance(fillet, Eigen::Vector3d(20 + r3 + 5, -10, 0)) == doctest::Approx(3));
  CHECK(face_distance(fillet, Eigen::Vector3d(20, -10 - r3 - 2 + 2 * std::cos(0.3), 2 - 2 * std::sin(0.3))) ==
        doctest::Approx(0).epsilon(1e-9));
}

TEST_CASE("analytic faces: excluded discs, turned faces, and bad input is refused") {
  // A plate with two holes: over a hole the distance is to the hole's rim.
  AnalyticFace plate;
  plate.lo = Eigen::Vector3d(-10, -10, 0);
  plate.hi = Eigen::Vector3d(10, 10, 0);
  plate.holes = {{Eigen::Vector3d(-5, 0, 0), 2}, {Eigen::Vector3d(5, 0, 0), 1}};
  CHECK(face_distance(plate, Eigen::Vector3d(-5, 0, 0)) == doctest::Approx(2));
  CHECK(face_distance(plate, Eigen::Vector3d(5, 0.5, 0)) == doctest::Approx(0.5));
  CHECK(face_distance(plate, Eigen::Vector3d(0, 0, 0.3)) == doctest::Approx(0.3));
  CHECK(face_distance(plate, Eigen::Vector3d(-5, 0, 1.5)) == doctest::Approx(2.5));  // 2 sideways, 1.5 up
  // Turned a quarter about x: the normal becomes -y, the box and holes follow.
  const Eigen::Matrix3d turn =
      Eigen::AngleAxisd(0.5 * 3.14159265358979323846, Eigen::Vector3d::UnitX()).toRotationMatrix();
  const AnalyticFace turned = rotated_face(plate, turn);
  CHECK(turned.axis.isApprox(-Eigen::Vector3d::UnitY()));
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(-5, 0, 0), Eigen::Vector3d(5, 0.5, 0), Eigen::Vector3d(0, 3, 0.3)})
    CHECK(face_distance(turned, turn * p) == doctest::Approx(face_distance(plate, p)));

  CHECK_THROWS_WITH(procedural_part_faces({"peg", {{"radius", -1}, {"length", 3}}, {}}), doctest::Contains("radius"));
  const std::vector<AnalyticFace> peg = procedural_part_faces({"peg", {{"radius", 1}, {"length", 3}}, {}});
  CHECK_THROWS_WITH(face_at(peg, Eigen::Vector3d::Zero(), 0.0, 0.1), doctest::Contains("must be > 0"));
  // Far from every face: no face.
  CHECK(face_at(peg, Eigen::Vector3d(10, 0, 1), 0.5, 0.1) == kNoFace);
  // On the side, mid-height: the side; on the top rim: an edge.
  CHECK(face_at(peg, Eigen::Vector3d(1, 0, 1.5), 0.5, 0.1) == find_face(peg, "peg side"));
  CHECK(face_at(peg, Eigen::Vector3d(1, 0, 3), 0.5, 0.1) == kEdge);
}
