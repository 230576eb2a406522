// scheduler/haptics/block_distances.h: both implementations against the grid's own
// double-precision sampler (sample_signed_distance), on the shipped peg's contact points
// moved about its own distance grid, partly off the grid's fine level and off the grid.
#include <doctest/doctest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/block_distances.h"
#include "scheduler/haptics/rigid_contact.h"

using namespace snapfit;

namespace {

struct Tally {
  std::size_t on_fine = 0, outside = 0, elsewhere = 0;
};

// Checks one implementation's distances for every block at rotation R and offset t (a
// block centre c at R c + t in the grid's frame) against sample_signed_distance.
template <class Distances>
void check_blocks(const ContactBlocks& blocks, const SignedDistanceGrid& grid, const Eigen::Matrix3d& R,
                  const Eigen::Vector3d& t, Distances distances, Tally& tally) {
  const FineDistanceView view(grid);
  double to_fine[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) to_fine[3 * r + c] = R(r, c) / grid.fine_spacing();
  for (const ShellChunk& block : blocks.blocks) {
    const Eigen::Vector3d centre = R * block.centre + t;
    BlockDistances out;
    REQUIRE(distances(blocks, block, to_fine, centre, grid, view, out));
    for (std::size_t i = 0; i < block.end - block.begin; ++i) {
      const std::size_t k = block.begin + i;
      const Eigen::Vector3d p = centre + R * Eigen::Vector3d(blocks.x[k], blocks.y[k], blocks.z[k]);
      const double exact = sample_signed_distance(grid, p, nullptr);
      if (out.node[i]) {
        ++tally.on_fine;
        // sample_signed_distance rounds the corners to float: 1e-7 of the band's distances.
        REQUIRE(std::abs(out.phi[i] - exact) <= 1e-6 * (grid.band + grid.coarse));
        REQUIRE(out.fx[i] >= -1e-12);
        REQUIRE(out.fx[i] <= 1 + 1e-12);
      } else if (out.outside[i]) {
        ++tally.outside;
        REQUIRE(exact > grid.band);
      } else {
        ++tally.elsewhere;
      }
    }
  }
}

}  // namespace

TEST_CASE("block distances: both implementations give the grid's trilinear distance at every contact point") {
  const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  const AssemblyPair pair = prepare_assembly_pair(scene);
  const auto model = rigid_contact_for(scene, pair.part(1).mesh, pair.part(2).mesh, pair.grids.spacing);
  REQUIRE(model);
  const SignedDistanceGrid& grid = model->part2_distance;  // the peg's points about its own grid: near zero
  const ContactBlocks& blocks = model->part2_blocks;
  const Eigen::Vector3d extent = (grid.dims.cast<double>() - Eigen::Vector3d::Ones()) * grid.coarse;

  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::vector<std::pair<Eigen::Matrix3d, Eigen::Vector3d>> poses = {{Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero()}};
  for (int q = 0; q < 6; ++q) {  // up to 3 degrees and 4 fine spacings off
    const Eigen::Vector3d axis = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    poses.push_back({Eigen::AngleAxisd(3 * M_PI / 180 * unit(random), axis).toRotationMatrix(),
                     4 * grid.fine_spacing() * Eigen::Vector3d(unit(random), unit(random), unit(random))});
  }
  poses.push_back({Eigen::Matrix3d::Identity(), 0.5 * extent});          // partly off the grid
  poses.push_back({Eigen::Matrix3d::Identity(), Eigen::Vector3d(0, 0, -3 * grid.band)});  // through the part

  Tally portable, avx2;
  for (const auto& [R, t] : poses) {
    check_blocks(blocks, grid, R, t, block_distances_portable, portable);
    if (block_distances_avx2_supported()) check_blocks(blocks, grid, R, t, block_distances_avx2, avx2);
  }
  MESSAGE("portable: " << portable.on_fine << " points on the fine level, " << portable.outside
                       << " outside beyond the band, " << portable.elsewhere << " elsewhere; AVX2 "
                       << std::string(block_distances_avx2_supported() ? "checked" : "not supported here"));
  CHECK(portable.on_fine > 0);
  CHECK(portable.outside > 0);
  CHECK(portable.elsewhere > 0);
  if (block_distances_avx2_supported()) {
    CHECK(avx2.on_fine == portable.on_fine);
    CHECK(avx2.outside == portable.outside);
    CHECK(avx2.elsewhere == portable.elsewhere);
  }
}
