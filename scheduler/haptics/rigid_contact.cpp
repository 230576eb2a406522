#include "scheduler/haptics/rigid_contact.h"

#include <cmath>
#include <optional>
#include <utility>

#include "mesh/fine_distance_view.h"
#include "mesh/mesh_report.h"
#include "pipeline/reach_region.h"
#include "scheduler/haptics/contact_block.h"
#include "scheduler/haptics/contact_cache.h"
#include "scheduler/haptics/contact_sum.h"
#include "snapfit/error.h"

namespace snapfit {

// The skin in fine grid spacings: the trilinear distance's largest error within the band
// of the shipped parts, where the distance has kinks (concave corners, polygon edges),
// was 0.29 spacings (tests/test_rigid_contact.cpp); touching surfaces must not push.
constexpr double kSkinPerSpacing = 0.35;

// The evaluation's blocks and groups of blocks are cubes this many sample spacings
// across: a smaller block lies clear of the other part more often, but each costs a
// distance lookup and a block's setup (6 and 18 were the fastest on the shipped scenes).
constexpr double kBlockSamples = 6, kGroupSamples = 18;

// Fine cells per coarse cell of the distance grids: with 3, a brick's z-slice of 4 x 4
// nodes is one cache line (mesh/signed_distance_grid.h), so a point's distance reads two
// lines; with 4 (5 x 5 slices) it read 2.75 on average.
constexpr int kContactRefine = 3;

namespace {

// What the geometry does not decide: stiffness, skin (from the distance spacing) and units.
void set_contact_parameters(RigidContactModel& m, double distance_spacing, double pressure_stiffness_n_per_m3,
                            double metres_per_unit) {
  if (!(std::isfinite(pressure_stiffness_n_per_m3) && pressure_stiffness_n_per_m3 > 0))
    throw Error("rigid contact: the contact stiffness must be > 0");
  if (!(std::isfinite(metres_per_unit) && metres_per_unit > 0)) throw Error("rigid contact: bad length unit");
  m.pressure_stiffness = pressure_stiffness_n_per_m3;
  m.skin = kSkinPerSpacing * distance_spacing;
  m.metres_per_unit = metres_per_unit;
}

}  // namespace

RigidContactModel build_rigid_contact(const Mesh& part1, const Mesh& part2, double sample_spacing,
                                      double distance_spacing, double band, double pressure_stiffness_n_per_m3,
                                      double metres_per_unit, const Eigen::AlignedBox3d* part1_region) {
  RigidContactModel m;
  set_contact_parameters(m, distance_spacing, pressure_stiffness_n_per_m3, metres_per_unit);
  std::optional<Eigen::AlignedBox3d> keep;  // the region grown by the band and a coarse cell
  if (part1_region) {
    keep = *part1_region;
    keep->min().array() -= band + 4 * distance_spacing;
    keep->max().array() += band + 4 * distance_spacing;
  }
  m.part1_distance = build_signed_distance_grid(part1, distance_spacing, band, band, kContactRefine, keep ? &*keep : nullptr);
  m.part2_distance = build_signed_distance_grid(part2, distance_spacing, band, band, kContactRefine);
  m.part1_samples = build_contact_samples(part1, sample_spacing, true);
  if (keep) m.part1_samples = samples_inside(m.part1_samples, *keep);
  m.part2_samples = build_contact_samples(part2, sample_spacing, false);
  prepare_rigid_contact(m);
  return m;
}

void prepare_rigid_contact(RigidContactModel& m) {
  for (auto [samples, blocks] :
       {std::pair(&m.part1_samples, &m.part1_blocks), std::pair(&m.part2_samples, &m.part2_blocks)})
    *blocks = build_contact_blocks(*samples, kBlockSamples * samples->spacing, kGroupSamples * samples->spacing);
}

std::shared_ptr<const RigidContactModel> rigid_contact_for(const Scene& scene, const Mesh& part1, const Mesh& part2,
                                                           double grid_spacing, std::string* why_off) {
  if (why_off) why_off->clear();
  if (!scene.haptics.contact || scene.method != Method::snapfit) return nullptr;
  for (int part = 1; part <= 2; ++part) {
    const MeshReport r = validate_mesh(part == 1 ? part1 : part2);
    if (r.watertight()) continue;
    if (why_off)
      *why_off = "rigid contact off: part " + std::to_string(part) + " is not watertight (" +
                 std::to_string(r.boundary_edges) + " open, " + std::to_string(r.non_manifold_edges) +
                 " non-manifold and " + std::to_string(r.inconsistent_edges) +
                 " inconsistently oriented edges), so its inside is not defined; seed 000's energy alone is "
                 "rendered (close the mesh, or set haptics.contact to false to silence this)";
    return nullptr;
  }
  const double samples = scene.haptics.contact_spacing.value_or(grid_spacing);
  const double distance = samples / 3;
  const double band = 2 * samples;
  const double u = metres_per_unit(scene.units);
  const double k = scene.haptics.contact_stiffness_n_per_mm3 * 1e9;
  // Part 1 only where part 2 can reach (pipeline/reach_region.h).
  const ReachRegion region = scene_region(scene, part1, part2, grid_spacing);
  const Eigen::AlignedBox3d* part1_region = region.bounded ? &region.box : nullptr;
  // The geometry from the contact cache (scheduler/haptics/contact_cache.h) when it has it.
  const std::string key = contact_cache_key(part1, part2, samples, distance, band, part1_region);
  RigidContactModel model;
  if (std::optional<RigidContactModel> cached = load_cached_contact(key)) {
    model = std::move(*cached);
    set_contact_parameters(model, distance, k, u);
  } else {
    model = build_rigid_contact(part1, part2, samples, distance, band, k, u, part1_region);
    save_cached_contact(key, model);  // not cached (unwritable folder, full disk): rebuilt next time
  }
  model.translation_only = scene.motion == Motion::translation;
  return std::make_shared<const RigidContactModel>(std::move(model));
}

namespace {

// Adds the contact of the blocks of `points` that take part, at this pose, in `share`.
void add_part_contact(const ContactBlocks& points, const SignedDistanceGrid& grid, const PointMap& map,
                      const Eigen::Vector3d& grid_offset, const Eigen::Vector3d& arm_offset, const ContactConstants& k,
                      std::size_t& group_index, std::size_t share, std::size_t shares, ContactSum& sum) {
  const FineDistanceView view(grid);
  for (const ShellChunk& group : points.groups)
    // Groups are dealt out in turn (group i to share i mod shares): a contact is
    // concentrated in space, and so in consecutive groups.
    if (group_index++ % shares == share)
      add_group_contact(points, group, map, grid_offset, arm_offset, grid, view, k, sum);
}

}  // namespace

ContactWrench contact_wrench_share(const RigidContactModel& m, const Pose& pose, std::size_t share,
                                   std::size_t shares) {
  if (m.part1_blocks.size() != m.part1_samples.points.size() || m.part2_blocks.size() != m.part2_samples.points.size())
    throw Error("rigid contact: the model's point blocks do not match its samples (call prepare_rigid_contact)");
  ContactSum sum;
  const double u = m.metres_per_unit;
  const ContactConstants k{m.skin, m.pressure_stiffness * u * u, u};
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix(), rt = r.transpose(),
                        identity = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d& t = pose.translation;
  std::size_t group_index = 0;
  // Part 2's points q in part 1's distance field: at R q + t, arm R q.
  add_part_contact(m.part2_blocks, m.part1_distance, point_map(r, r, identity, 1, m.part1_distance), t,
                   Eigen::Vector3d::Zero(), k, group_index, share, shares, sum);
  // Part 1's edge points x in part 2's: at R^T (x - t), arm x - t, gradient R grad phi_2,
  // derivatives negated.
  add_part_contact(m.part1_blocks, m.part2_distance, point_map(rt, identity, r, -1, m.part2_distance), -(rt * t), -t, k,
                   group_index, share, shares, sum);
  return sum.wrench();
}

void add_contact_share(ContactWrench& sum, const ContactWrench& share) {
  sum.energy_j += share.energy_j;
  sum.wrench.force += share.wrench.force;
  sum.wrench.torque += share.wrench.torque;
  sum.stiffness += share.stiffness;
  sum.points += share.points;
  sum.depth = std::max(sum.depth, share.depth);
}

void finish_contact(const RigidContactModel& m, ContactWrench& c) {
  c.stiffness.triangularView<Eigen::StrictlyUpper>() = c.stiffness.transpose();
  if (m.translation_only) {  // the part cannot turn: the wrench's rotational part is not rendered
    c.wrench.torque.setZero();
    c.stiffness.rightCols<3>().setZero();
    c.stiffness.bottomRows<3>().setZero();
  }
}

RigidContactFacts rigid_contact_facts(const RigidContactModel& m) {
  RigidContactFacts f;
  f.pressure_stiffness_n_per_mm3 = m.pressure_stiffness * 1e-9;  // N/m^3 -> N/mm^3
  f.sample_spacing = m.part2_samples.spacing;
  f.distance_spacing = m.part1_distance.fine_spacing();
  f.skin = m.skin;
  f.part1_edge_points = m.part1_samples.points.size();
  f.part2_points = m.part2_samples.points.size();
  return f;
}

ContactWrench contact_wrench(const RigidContactModel& m, const Pose& pose) {
  ContactWrench c = contact_wrench_share(m, pose, 0, 1);
  finish_contact(m, c);
  return c;
}

}  // namespace snapfit
