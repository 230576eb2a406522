// The direct reference (engine/query/direct_reference.h) on the shipped peg and hole, made
// small: part 2's descriptors evaluated from its mesh at arbitrary points equal its grid
// fields at the grid's points, and at poses that map part 1's lattice onto part 2's (R = I
// and a half turn, lattice translations) the direct sum equals the untruncated spectral
// sum of the sampled fields (engine/query/reference_query.h, double precision).
#include <doctest/doctest.h>

#include "engine/query/direct_reference.h"
#include "engine/query/reference_query.h"
#include "tests/stability_support.h"

namespace snapfit {
namespace {

// The pose of part 2 that puts its grid point `n2` on part 1's grid point `n1`, turned by R.
Pose lattice_pose(const AssemblyPair& pair, const Eigen::Matrix3d& R, const Eigen::Vector3i& n1,
                  const Eigen::Vector3i& n2) {
  Pose pose;
  pose.rotation = Eigen::Quaterniond(R);
  pose.translation = pair.grid(1).point(n1.x(), n1.y(), n1.z()) - R * pair.grid(2).point(n2.x(), n2.y(), n2.z());
  return pose;
}

}  // namespace

TEST_CASE("direct reference: part 2's descriptors at its own grid points equal its grid fields") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  const GridSpec& g2 = pair.grid(2);
  std::vector<Eigen::Vector3d> points;
  std::vector<std::size_t> index;
  for (std::size_t i = 0; i < g2.count(); i += 7) {
    points.push_back(g2.point(i));
    index.push_back(i);
  }
  DescriptorOptions options;
  options.program_cache = test::test_program_cache();
  const DescriptorFields at = descriptors_at_points(test::test_context(), pair.part(2).mesh, points, g2.origin,
                                                    g2.spacing, pair.scene.descriptor, options);
  const DescriptorFields& grid = pair.fields(2).fields;
  REQUIRE(at.skeletal_density.size() == points.size());
  for (std::size_t n = 0; n < points.size(); ++n) {
    const std::size_t i = index[n];
    CAPTURE(i);
    CHECK((at.winding[n] >= 0.5f) == (grid.winding[i] >= 0.5f));
    CHECK(at.signed_distance[n] == grid.signed_distance[i]);
    CHECK(at.skeletal_density[n] == grid.skeletal_density[i]);
  }
}

TEST_CASE("direct reference: equals the untruncated spectral sum at lattice poses, identity and half turn") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  DirectReferenceOptions options;
  options.descriptors.program_cache = test::test_program_cache();
  const DirectReference direct(test::test_context(), pair.fields(1).fields, pair.part(2).mesh, pair.grid(2), options);
  // Part 2's grid point n2 on part 1's n1: in free space, touching, and deep in the hole.
  const Eigen::Vector3i c1 = pair.grid(1).dims / 2, c2 = pair.grid(2).dims / 2;
  const Eigen::Matrix3d half_turn = Eigen::Vector3d(-1, -1, 1).asDiagonal();
  std::vector<Pose> poses;
  for (const Eigen::Matrix3d& R : {Eigen::Matrix3d(Eigen::Matrix3d::Identity()), half_turn})
    for (int dz : {-6, 0, 8}) poses.push_back(lattice_pose(pair, R, c1 + Eigen::Vector3i(0, 0, dz), c2));
  const std::vector<QueryResult> d = direct.evaluate(poses);
  ReferenceOptions spectral;
  spectral.modes = 0;  // every mode
  spectral.force = spectral.torque = false;
  for (std::size_t n = 0; n < poses.size(); ++n) {
    CAPTURE(n);
    const QueryResult s = reference_query(pair.spectra, poses[n], spectral);
    REQUIRE(s.flags == query_ok);
    REQUIRE(d[n].flags == query_ok);
    CHECK(std::abs(d[n].energy) > 0);
    // Float fields and float spectra: agreement to their round-off.
    CHECK(d[n].energy == doctest::Approx(s.energy).epsilon(1e-5));
  }
}

TEST_CASE("direct reference: its force is the spectral sum's central difference at lattice poses") {
  const AssemblyPair pair = test::build_small_pair(test::small_peg_hole_scene());
  DirectReferenceOptions options;
  options.descriptors.program_cache = test::test_program_cache();
  options.translation_step = pair.grid(1).spacing;  // neighbouring lattice poses
  options.torque = false;
  const DirectReference direct(test::test_context(), pair.fields(1).fields, pair.part(2).mesh, pair.grid(2), options);
  const Eigen::Vector3i c1 = pair.grid(1).dims / 2, c2 = pair.grid(2).dims / 2;
  const Pose pose = lattice_pose(pair, Eigen::Matrix3d::Identity(), c1 + Eigen::Vector3i(1, 0, 2), c2);
  const QueryResult d = direct.evaluate({pose})[0];
  ReferenceOptions spectral;
  spectral.modes = 0;
  spectral.force = spectral.torque = false;
  for (int a = 0; a < 3; ++a) {
    CAPTURE(a);
    Pose up = pose, down = pose;
    up.translation[a] += options.translation_step;
    down.translation[a] -= options.translation_step;
    const double slope =
        (reference_query(pair.spectra, up, spectral).energy - reference_query(pair.spectra, down, spectral).energy) /
        (2 * options.translation_step);
    CHECK(d.force[a] == doctest::Approx(-slope).epsilon(1e-4).scale(1e-6 * std::abs(d.energy)));
  }
}

}  // namespace snapfit
