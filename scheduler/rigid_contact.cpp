#include "scheduler/rigid_contact.h"

#include <cmath>

#include "mesh/mesh_report.h"
#include "scheduler/contact_cache.h"
#include "snapfit/error.h"

namespace snapfit {

// The skin in fine grid spacings: the trilinear distance's largest error within the band
// of the shipped parts, where the distance has kinks (concave corners, polygon edges),
// was 0.29 spacings (tests/test_rigid_contact.cpp); touching surfaces must not push.
constexpr double kSkinPerSpacing = 0.35;

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
                                      double metres_per_unit) {
  RigidContactModel m;
  set_contact_parameters(m, distance_spacing, pressure_stiffness_n_per_m3, metres_per_unit);
  m.part1_distance = build_signed_distance_grid(part1, distance_spacing, band, band);
  m.part2_distance = build_signed_distance_grid(part2, distance_spacing, band, band);
  m.part1_samples = build_contact_samples(part1, sample_spacing, true);
  m.part2_samples = build_contact_samples(part2, sample_spacing, false);
  return m;
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
  // The geometry from the contact cache (scheduler/contact_cache.h) when it has it.
  const std::string key = contact_cache_key(part1, part2, samples, distance, band);
  RigidContactModel model;
  if (std::optional<RigidContactModel> cached = load_cached_contact(key)) {
    model = std::move(*cached);
    set_contact_parameters(model, distance, k, u);
  } else {
    model = build_rigid_contact(part1, part2, samples, distance, band, k, u);
    save_cached_contact(key, model);  // not cached (unwritable folder, full disk): rebuilt next time
  }
  model.translation_only = scene.motion == Motion::translation;
  return std::make_shared<const RigidContactModel>(std::move(model));
}

namespace {

// Adds one point's term: phi (scene units, < -skin), its derivatives j_t (per unit of
// translation) and j_r (per radian, scene units), and k_a = k A (N / m per m of depth).
void add_term(ContactWrench& c, double phi, double skin, const Eigen::Vector3d& j_t, const Eigen::Vector3d& j_r,
              double k_a, double u) {
  const double phi_m = u * (phi + skin);
  c.energy_j += 0.5 * k_a * phi_m * phi_m;
  c.wrench.force -= k_a * phi_m * j_t;
  c.wrench.torque -= k_a * phi_m * u * j_r;
  Eigen::Matrix<double, 6, 1> j;
  j << j_t, u * j_r;
  c.stiffness.selfadjointView<Eigen::Lower>().rankUpdate(j, k_a);
  ++c.points;
  c.depth = std::max(c.depth, -phi);
}

}  // namespace

ContactWrench contact_wrench_share(const RigidContactModel& m, const Pose& pose, std::size_t share,
                                   std::size_t shares) {
  ContactWrench c;
  const double u = m.metres_per_unit;
  const double k_area = m.pressure_stiffness * u * u;  // N / m per m of depth, per scene unit^2 of area
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  const Eigen::Vector3d& t = pose.translation;
  // Chunks are dealt out in turn (chunk i to share i mod shares): a contact is
  // concentrated in space, and so in consecutive chunks.
  std::size_t chunk_index = 0;
  const auto mine = [&] { return chunk_index++ % shares == share; };
  // Part 2's points in part 1's distance field.
  const ContactSamples& s2 = m.part2_samples;
  const double skin2 = m.part1_distance.fine_spacing();
  for (const ShellChunk& chunk : s2.chunks) {
    if (!mine()) continue;
    if (sample_signed_distance(m.part1_distance, r * chunk.centre + t, nullptr) > chunk.radius + skin2) continue;
    for (std::size_t i = chunk.begin; i < chunk.end; ++i) {
      const Eigen::Vector3d arm = r * s2.points[i];
      Eigen::Vector3d g;
      const double phi = sample_signed_distance(m.part1_distance, arm + t, &g);
      if (phi < -m.skin) add_term(c, phi, m.skin, g, arm.cross(g), k_area * s2.areas[i], u);
    }
  }
  // Part 1's edge points in part 2's distance field.
  const ContactSamples& s1 = m.part1_samples;
  const Eigen::Matrix3d rt = r.transpose();
  const double skin1 = m.part2_distance.fine_spacing();
  for (const ShellChunk& chunk : s1.chunks) {
    if (!mine()) continue;
    if (sample_signed_distance(m.part2_distance, rt * (chunk.centre - t), nullptr) > chunk.radius + skin1) continue;
    for (std::size_t i = chunk.begin; i < chunk.end; ++i) {
      const Eigen::Vector3d arm = s1.points[i] - t;
      Eigen::Vector3d g2;
      const double phi = sample_signed_distance(m.part2_distance, rt * arm, &g2);
      if (phi < -m.skin) {
        const Eigen::Vector3d g = r * g2;
        add_term(c, phi, m.skin, -g, -arm.cross(g), k_area * s1.areas[i], u);
      }
    }
  }
  return c;
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

ContactWrench contact_wrench(const RigidContactModel& m, const Pose& pose) {
  ContactWrench c = contact_wrench_share(m, pose, 0, 1);
  finish_contact(m, c);
  return c;
}

}  // namespace snapfit
