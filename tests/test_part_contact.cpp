// The contact report.html shows (report/part_contact.h): triangles of one shipped part
// inside the other, by the other's winding-number field on its grid, against the exact
// generalized winding number in double (tests/descriptor_reference.h) wherever the point
// is more than 1.5 grid spacings from the other part's surface.
#include <doctest/doctest.h>
#include <string>

#include "engine/fields/descriptors.h"
#include "pipeline/assembly_pair.h"
#include "report/part_contact.h"
#include "report/run_page.h"
#include "snapfit/error.h"
#include "tests/descriptor_reference.h"
#include "tests/test_engine_support.h"

using namespace snapfit;

namespace {

DescriptorFields winding_field(const Mesh& mesh, const GridSpec& grid) {
  DescriptorParams indicator;
  indicator.kind = DescriptorKind::indicator;
  DescriptorOptions options;
  options.program_cache = test::test_program_cache();
  return compute_descriptors(test::test_context(), mesh, grid, indicator, options);
}

struct Agreement {
  int inside = 0, outside = 0, disagree = 0, near_surface = 0;
};

// Every `stride`-th point: the flag against the exact winding number of `other` at the
// placed point, where that point is farther than `band` from other's surface.
Agreement compare(const std::vector<Eigen::Vector3d>& points, const std::vector<std::uint8_t>& bits, const Pose& pose,
                  const Mesh& other, double band, std::size_t stride) {
  Agreement a;
  for (std::size_t i = 0; i < points.size(); i += stride) {
    const Eigen::Vector3d p = pose.apply(points[i]);
    if (test::reference_distance(other, p) <= band) {
      ++a.near_surface;
      continue;
    }
    const bool exact = test::reference_winding(other, p) > 0.5;
    const bool flagged = (bits[i / 8] >> (i % 8)) & 1;
    a.disagree += exact != flagged;
    (exact ? a.inside : a.outside) += 1;
  }
  return a;
}

}  // namespace

TEST_CASE("part contact: inside flags of the default scene's parts agree with the exact winding number") {
  const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  const AssemblyPair pair = prepare_assembly_pair(scene);
  const double h = pair.grids.spacing;
  const Mesh& block = pair.part(1).mesh;
  const Mesh& peg = pair.part(2).mesh;
  const DescriptorFields w1 = winding_field(block, pair.grid(1));
  const DescriptorFields w2 = winding_field(peg, pair.grid(2));
  const PartVolume volume1{&pair.grid(1), &w1.winding}, volume2{&pair.grid(2), &w2.winding};

  // What the page shows: the display meshes' triangle centres.
  const RunPageLimits limits;
  const Mesh shown_block = display_mesh(block, h, limits.display_triangles);
  const Mesh shown_peg = display_mesh(peg, h, limits.display_triangles);
  CHECK(shown_peg.triangles.size() > peg.triangles.size());
  const std::vector<Eigen::Vector3d> c1 = triangle_centroids(shown_block), c2 = triangle_centroids(shown_peg);
  const std::size_t stride1 = std::max<std::size_t>(1, c1.size() / 1500),
                    stride2 = std::max<std::size_t>(1, c2.size() / 1500);

  struct Case {
    const char* name;
    Pose pose;
    bool expect_inside;
  };
  Pose start = scene.part2.pose, shifted, assembled = *scene.assembled_pose;
  shifted.translation = Eigen::Vector3d(3, 0, -10);  // half inserted, 3 mm into the hole's wall
  for (const Case& c :
       {Case{"start", start, false}, Case{"assembled", assembled, false}, Case{"shifted", shifted, true}}) {
    CAPTURE(c.name);
    const std::vector<std::uint8_t> in2 = points_inside(c2, c.pose, volume1);
    const std::vector<std::uint8_t> in1 = points_inside(c1, c.pose.inverse(), volume2);
    const Agreement a2 = compare(c2, in2, c.pose, block, 1.5 * h, stride2);
    const Agreement a1 = compare(c1, in1, c.pose.inverse(), peg, 1.5 * h, stride1);
    MESSAGE(std::string(c.name) << ": peg in block " << a2.inside << " inside, " << a2.outside << " outside, "
                                << a2.near_surface << " near the surface; block in peg " << a1.inside << " inside, "
                                << a1.outside << " outside");
    CHECK(a2.disagree == 0);
    CHECK(a1.disagree == 0);
    if (c.expect_inside) {
      CHECK(a2.inside >= 50);
      CHECK(a1.inside >= 20);
    } else {
      CHECK(a2.inside == 0);
      CHECK(a1.inside == 0);
    }
    CHECK(a2.outside >= 50);
  }
  CHECK_THROWS_AS(points_inside(c2, start, PartVolume{&pair.grid(1), &w2.winding}), Error);
}
