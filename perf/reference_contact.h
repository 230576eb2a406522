#pragma once
// The rigid contact's straightforward evaluation (scheduler/haptics/rigid_contact.h's sum, as the
// engine evaluated it before its point blocks), for bench_contact's reference rows: the
// samples' chunks (8 sample spacings across) skipped when their centre's distance exceeds
// their radius plus a fine spacing, every other point's distance and gradient in double,
// each term's stiffness by Eigen's rank update.
#include "scheduler/haptics/rigid_contact.h"

namespace snapfit::bench {

namespace reference_detail {

inline void add_term(ContactWrench& c, double phi, double skin, const Eigen::Vector3d& j_t, const Eigen::Vector3d& j_r,
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

}  // namespace reference_detail

// A ContactShareFunction (scheduler/haptics/parallel_contact.h).
inline ContactWrench reference_contact_share(const RigidContactModel& m, const Pose& pose, std::size_t share,
                                             std::size_t shares) {
  using reference_detail::add_term;
  ContactWrench c;
  const double u = m.metres_per_unit;
  const double k_area = m.pressure_stiffness * u * u;
  const Eigen::Matrix3d r = pose.rotation.toRotationMatrix();
  const Eigen::Vector3d& t = pose.translation;
  std::size_t chunk_index = 0;
  const auto mine = [&] { return chunk_index++ % shares == share; };
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

}  // namespace snapfit::bench
