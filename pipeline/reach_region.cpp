#include "pipeline/reach_region.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "pipeline/part_fields.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

// The fade outside the region, in grid spacings: wide enough that the window's
// transform decays well before the highest frequencies the queries sum.
constexpr double kFadeSpacings = 4;

Eigen::AlignedBox3d grid_box(const GridSpec& g) {
  return Eigen::AlignedBox3d(g.origin, g.origin + g.spacing * (g.dims.cast<double>().array() - 1.0).matrix());
}

// The distance from part 2's origin to the farthest corner of its box: how far any of
// the box reaches from the origin at any orientation.
double farthest_corner(const Eigen::AlignedBox3d& box) {
  double reach = 0;
  for (int c = 0; c < 8; ++c)
    reach = std::max(reach, box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)).norm());
  return reach;
}

// Grows `region` by part 2's box at `pose` (its 8 corners).
void add_box_at(const Eigen::AlignedBox3d& box, const Pose& pose, Eigen::AlignedBox3d& region) {
  for (int c = 0; c < 8; ++c) region.extend(pose.apply(box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c))));
}

// Part 2's box swept along the keyframes: steps of at most half a spacing at its farthest corner.
Eigen::AlignedBox3d swept_box(const std::vector<Keyframe>& keys, const Eigen::AlignedBox3d& box, double radius,
                              double spacing, bool rotates) {
  Eigen::AlignedBox3d region;
  auto rotation_of = [&](const Keyframe& k) {
    return rotates ? k.pose.rotation.normalized() : Eigen::Quaterniond::Identity();
  };
  for (std::size_t i = 0; i < keys.size(); ++i) {
    Pose a{rotation_of(keys[i]), keys[i].pose.translation};
    add_box_at(box, a, region);
    if (i + 1 == keys.size()) break;
    const Pose b{rotation_of(keys[i + 1]), keys[i + 1].pose.translation};
    const double travel = (b.translation - a.translation).norm() + radius * a.rotation.angularDistance(b.rotation);
    const int steps = static_cast<int>(std::min(100000.0, std::ceil(travel / (0.5 * spacing))));
    for (int s = 1; s < steps; ++s) {
      const double f = double(s) / steps;
      const Pose p{a.rotation.slerp(f, b.rotation), (1 - f) * a.translation + f * b.translation};
      add_box_at(box, p, region);
    }
  }
  return region;
}

std::string box_text(const Eigen::AlignedBox3d& b) {
  std::ostringstream s;
  s.precision(4);
  const Eigen::Vector3d size = b.sizes();
  s << size.x() << " x " << size.y() << " x " << size.z();
  return s.str();
}

}  // namespace

ReachRegion reach_region(const Scene& scene, const GridSpec& part2_grid) {
  ReachRegion r;
  const Eigen::AlignedBox3d box = grid_box(part2_grid);
  r.part2_box = box;
  const double radius = farthest_corner(box);
  r.margin = scene.grid.region.margin.value_or(0.25 * box.diagonal().norm());
  r.fade = kFadeSpacings * part2_grid.spacing;
  const RegionParams& p = scene.grid.region;
  const bool rotates = scene.motion != Motion::translation;
  if (p.kind == RegionKind::whole) {
    r.reason = "part 1's grid covers all of it (grid.region \"whole\")";
    return r;
  }
  if (p.kind == RegionKind::reach && scene.trajectory.keyframes.empty()) {
    r.reason = "part 1's grid covers all of it: the scene has no trajectory to say where part 2 goes "
               "(grid.region may declare a workspace)";
    return r;
  }
  if (p.kind == RegionKind::workspace) {
    // Any orientation: the ball about part 2's origin that holds its box.
    if (!rotates) {
      r.box = Eigen::AlignedBox3d(p.workspace_min + box.min(), p.workspace_max + box.max());
    } else {
      r.box = Eigen::AlignedBox3d(p.workspace_min.array() - radius, p.workspace_max.array() + radius);
    }
    r.reason = "the declared workspace (grid.region)";
  } else {
    std::vector<Keyframe> keys = scene.trajectory.keyframes;
    Keyframe start;
    start.pose = scene.part2.pose;
    keys.insert(keys.begin(), start);  // the part starts at its scene pose
    r.box = swept_box(keys, box, radius, part2_grid.spacing, rotates);
    r.reason = "part 2's grid box swept along the trajectory";
  }
  r.box.min().array() -= r.margin;
  r.box.max().array() += r.margin;
  r.bounded = r.box_known = true;
  std::ostringstream why;
  why.precision(4);
  why << r.reason << ", plus a margin of " << r.margin << " " << scene.units << " (" << box_text(r.box) << " "
      << scene.units << ")";
  r.reason = why.str();
  return r;
}

ReachRegion scene_region(const Scene& scene, const GridSpec& part1_grid, const GridSpec& part2_grid) {
  ReachRegion region = reach_region(scene, part2_grid);
  region.part1_grid = part1_grid;
  if (!region.bounded) return region;
  const auto keep_whole = [&](const std::string& why) {
    region.bounded = false;
    region.reason = "part 1's grid covers all of it: " + why;
    return region;
  };
  if (scene.method != Method::snapfit) return keep_whole("the region applies to seed 000's fields only");
  if (scene.part1.descriptor.source != SpectrumSource::grid || scene.part2.descriptor.source != SpectrumSource::grid)
    return keep_whole("a part's spectrum comes from spheres");
  Eigen::AlignedBox3d keep = region.box;
  keep.min().array() -= region.fade + part1_grid.spacing;
  keep.max().array() += region.fade + part1_grid.spacing;
  if (!keep.intersects(grid_box(part1_grid))) return keep_whole("part 2 never reaches part 1's grid");
  const GridSpec cropped = crop_grid(part1_grid, keep);
  if (cropped.count() == part1_grid.count()) return keep_whole("the region part 2 reaches holds it (" + region.reason + ")");
  std::ostringstream why;
  why << "part 1's grid covers the region part 2 reaches: " << region.reason << "; " << cropped.dims.x() << " x "
      << cropped.dims.y() << " x " << cropped.dims.z() << " points of " << part1_grid.dims.x() << " x "
      << part1_grid.dims.y() << " x " << part1_grid.dims.z();
  region.reason = why.str();
  region.part1_grid = cropped;
  return region;
}

ReachRegion scene_region(const Scene& scene, const Mesh& part1, const Mesh& part2, double spacing) {
  return scene_region(scene, part_grid(part1, scene.grid, spacing), part_grid(part2, scene.grid, spacing));
}

GridSpec crop_grid(const GridSpec& full, const Eigen::AlignedBox3d& keep) {
  GridSpec out = full;
  for (int a = 0; a < 3; ++a) {
    const double lo = (keep.min()[a] - full.origin[a]) / full.spacing;
    const double hi = (keep.max()[a] - full.origin[a]) / full.spacing;
    const int first = std::max(0, static_cast<int>(std::floor(lo + 1e-9)));
    const int last = std::min(full.dims[a] - 1, static_cast<int>(std::ceil(hi - 1e-9)));
    if (last < first) throw Error("crop_grid: the box kept does not overlap the grid");
    out.origin[a] = full.origin[a] + first * full.spacing;
    out.dims[a] = last - first + 1;
  }
  return out;
}

void fade_outside(const GridSpec& grid, const Eigen::AlignedBox3d& box, double fade, std::vector<float>& values) {
  if (values.size() != grid.count()) throw Error("fade_outside: the values do not match the grid");
  const double pi = 3.14159265358979323846;
  for (int k = 0; k < grid.dims.z(); ++k)
    for (int j = 0; j < grid.dims.y(); ++j)
      for (int i = 0; i < grid.dims.x(); ++i) {
        const Eigen::Vector3d p = grid.point(i, j, k);
        const double d = box.exteriorDistance(p);
        if (d <= 0) continue;
        const double w = d >= fade ? 0.0 : 0.5 * (1 + std::cos(pi * d / fade));
        values[grid.index(i, j, k)] *= static_cast<float>(w);
      }
}

bool pose_in_region(const ReachRegion& region, const Pose& pose) {
  if (!region.bounded) return true;
  for (int c = 0; c < 8; ++c)
    if (!region.box.contains(pose.apply(region.part2_box.corner(static_cast<Eigen::AlignedBox3d::CornerType>(c)))))
      return false;
  return true;
}

}  // namespace snapfit
