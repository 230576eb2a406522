// inspect_mesh_file (include/snapfit/inspect.h) against closed forms: a box's triangles,
// area and volume (scaled), and a STEP solid's mesh against OpenCASCADE's exact volume.
#include <cmath>
#include <doctest/doctest.h>

#include "io/mesh_export.h"
#include "snapfit/error.h"
#include "snapfit/inspect.h"
#include "tests/test_meshes.h"
#include "tests/test_support.h"

using namespace snapfit;

TEST_CASE("inspect_mesh_file: a box's counts, area and volume, at a scale") {
  const test::TempDir dir;
  const std::string path = dir.file("box.stl");
  write_stl(test::box_mesh(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3)), path);
  MeshFileRequest request;
  request.file = path;
  request.scale = 2;
  const MeshFileReport report = inspect_mesh_file(request);
  CHECK(!report.cad);
  CHECK(report.mesh.triangle_count == 12);
  CHECK(report.mesh.vertex_count == 8);
  CHECK(report.mesh.watertight());
  CHECK(report.mesh.enclosed_volume == doctest::Approx(8 * 6.0));
  CHECK(report.mesh.surface_area == doctest::Approx(4 * 2 * (2 + 3 + 6.0)));
  CHECK(report.mesh.bbox_max.isApprox(Eigen::Vector3d(2, 4, 6)));
  CHECK(format_mesh_report(report.mesh).find("12") != std::string::npos);
}

TEST_CASE("inspect_mesh_file: a STEP solid's mesh against its exact volume, in the units asked for") {
  MeshFileRequest request;
  request.file = std::string(SNAPFIT_SOURCE_DIR) + "/scenes/parts/peg.step";
  const MeshFileReport mm = inspect_mesh_file(request);
  REQUIRE(mm.cad);
  CHECK(mm.cad->format == "STEP");
  CHECK(mm.mesh.watertight());
  CHECK(mm.mesh.enclosed_volume == doctest::Approx(mm.cad->exact_volume).epsilon(0.02));
  request.metres_per_unit = 1e-2;  // cm
  const MeshFileReport cm = inspect_mesh_file(request);
  REQUIRE(cm.cad);
  CHECK(cm.cad->exact_volume == doctest::Approx(mm.cad->exact_volume * 1e-3));
}

TEST_CASE("inspect_mesh_file: a missing file is named") {
  MeshFileRequest request;
  request.file = "/nonexistent/part.stl";
  CHECK_THROWS_WITH_AS(inspect_mesh_file(request), doctest::Contains("/nonexistent/part.stl"), Error);
}
