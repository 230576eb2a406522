#pragma once
// The region of part 1 a scene needs (docs/scenes.md "Grid", docs/design.md "Leave out
// what a scene does not need"): where part 2's field can be at the poses the scene allows,
// plus a margin. Seed 000's energy is an integral of rho_1 times the moved rho_2, so rho_1
// matters only where rho_2 can reach: part 1's grid, fields, spectra and contact cover that
// region, and fade to zero over a few grid spacings outside it (a smooth edge instead of a
// cut, so the crop adds no high frequencies the truncated sum would have to resolve).
#include <Eigen/Geometry>
#include <string>

#include "mesh/mesh.h"
#include "snapfit/grid.h"
#include "snapfit/scene.h"

namespace snapfit {

struct ReachRegion {
  bool bounded = false;     // false: all of part 1
  bool box_known = false;   // `box` says where part 2 can be, whether or not part 1's grid is cut to it
  Eigen::AlignedBox3d box;  // part 1's frame: part 2's grid box at every allowed pose, plus the margin
  double margin = 0;        // scene units
  double fade = 0;          // width of the fade outside `box`, scene units
  Eigen::AlignedBox3d part2_box;  // part 2's grid box in its own frame (the per-frame check)
  GridSpec part1_grid;            // scene_region: part 1's grid, cropped to the region when bounded
  std::string reason;  // one sentence: where the region comes from, or why it is all of part 1
};

// The region of `scene.grid.region` for part 2's grid `part2_grid` (in the frame its
// queries use: for translation-only motion its orientation is baked into the mesh, and
// poses are translations). `reach` sweeps the grid box along the trajectory's keyframes
// (positions linear, rotations by slerp, in steps of at most half a grid spacing at the
// box's far corner); without a trajectory it is all of part 1.
ReachRegion reach_region(const Scene& scene, const GridSpec& part2_grid);

// The region of a scene's pair and part 1's grid cut down to it, with room for the fade:
// bounded only for seed 000's grid fields (Voxmap PointShell and seed 001's spheres keep
// the whole part) and only when it leaves out some of part 1's grid.
ReachRegion scene_region(const Scene& scene, const GridSpec& part1_grid, const GridSpec& part2_grid);
// The same from the parts' meshes at the scene's common grid spacing.
ReachRegion scene_region(const Scene& scene, const Mesh& part1, const Mesh& part2, double spacing);

// The sub-grid of `full` (the same points) that covers `keep`; `full` itself when it
// lies inside. Throws snapfit::Error when they do not overlap.
GridSpec crop_grid(const GridSpec& full, const Eigen::AlignedBox3d& keep);

// Multiplies `values` (on `grid`) by a window that is 1 inside `box` and falls to 0 as
// (1 + cos(pi d / fade)) / 2 over a distance d = fade outside it (d: Euclidean distance to
// the box), 0 beyond.
void fade_outside(const GridSpec& grid, const Eigen::AlignedBox3d& box, double fade, std::vector<float>& values);

// True when part 2's grid box at `pose` lies inside the region (always, when not bounded).
bool pose_in_region(const ReachRegion& region, const Pose& pose);

}  // namespace snapfit
