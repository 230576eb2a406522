// Analytic faces of the procedural parts (mesh/analytic_faces.h, procedural_parts.h):
// every shell point of a chamfered peg maps to the face its position says, or to an edge
// within the edge band of a profile corner; every surface voxel of a hole block maps to a
// face, the wall's voxels to the wall; radii differ by the clearance; bad input.
#include <doctest/doctest.h>
#include <cmath>
#include <cstring>

#include "mesh/analytic_faces.h"
#include "mesh/procedural/procedural_parts.h"
#include "mesh/voxmap.h"
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

TEST_CASE("analytic faces: the three-peg pair has none, and bad input is refused") {
  const ProceduralPartSpec base{"three_peg_base",
                                {{"cell", 20}, {"base_thickness", 5}, {"cover_thickness", 5}},
                                {{"peg_radii", {3, 4, 5}}, {"peg_heights", {6, 8, 10}}, {"fillet_radii", {1, 1, 1}}}};
  CHECK(procedural_part_faces(base).empty());
  CHECK_THROWS_WITH(procedural_part_faces({"peg", {{"radius", -1}, {"length", 3}}, {}}), doctest::Contains("radius"));
  const std::vector<AnalyticFace> peg = procedural_part_faces({"peg", {{"radius", 1}, {"length", 3}}, {}});
  CHECK_THROWS_WITH(face_at(peg, Eigen::Vector3d::Zero(), 0.0, 0.1), doctest::Contains("must be > 0"));
  // Far from every face: no face.
  CHECK(face_at(peg, Eigen::Vector3d(10, 0, 1), 0.5, 0.1) == kNoFace);
  // On the side, mid-height: the side; on the top rim: an edge.
  CHECK(face_at(peg, Eigen::Vector3d(1, 0, 1.5), 0.5, 0.1) == find_face(peg, "peg side"));
  CHECK(face_at(peg, Eigen::Vector3d(1, 0, 3), 0.5, 0.1) == kEdge);
}
