#include "engine/query/direct_reference.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "snapfit/error.h"

namespace snapfit {
namespace {

// R -> exp(angle [axis]x) R: a rotation increment on the left, about part 2's origin.
Pose turned(const Pose& pose, const Eigen::Vector3d& axis, double angle) {
  Pose out = pose;
  out.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis)) * pose.rotation;
  return out;
}

}  // namespace

DirectReference::DirectReference(const ComputeContext& ctx, const DescriptorFields& part1, const Mesh& part2_mesh,
                                 const GridSpec& part2_grid, const DirectReferenceOptions& options)
    : ctx_(ctx),
      part1_(part1),
      rho1_(affinity_imaginary(part1)),
      part2_mesh_(part2_mesh),
      part2_grid_(part2_grid),
      options_(options) {
  if (part1.winding.empty() || part1.grid.count() != part1.winding.size())
    throw Error("direct reference: part 1's fields are empty or do not match their grid");
  if (part2_grid.count() == 0) throw Error("direct reference: part 2's grid is empty");
  if (std::abs(part1.grid.spacing - part2_grid.spacing) > 1e-9 * part1.grid.spacing)
    throw Error("direct reference: the parts' grids have different spacings");
  const double h = part2_grid.spacing;
  translation_step_ = options.translation_step > 0 ? options.translation_step : 0.5 * h;
  double r_max = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3i c((corner & 1) ? part2_grid.dims.x() - 1 : 0, (corner & 2) ? part2_grid.dims.y() - 1 : 0,
                            (corner & 4) ? part2_grid.dims.z() - 1 : 0);
    r_max = std::max(r_max, part2_grid.point(c.x(), c.y(), c.z()).norm());
  }
  rotation_step_ = options.rotation_step > 0 ? options.rotation_step : 0.5 * h / std::max(r_max, h);
}

std::vector<QueryResult> DirectReference::evaluate(const std::vector<Pose>& poses) const {
  const GridSpec& g1 = part1_.grid;
  const GridSpec& g2 = part2_grid_;
  const double h = g1.spacing, h3 = h * h * h;
  // E = -Re f with rho = i a (the affinity's samples are imaginary for both kinds:
  // engine/spectra/spectra.h), so Re(rho1 rho2) = -a1 a2 and E = h^3 sum a1 a2.
  const Eigen::Vector3d lo = g2.origin - Eigen::Vector3d::Constant(0.5 * h);
  const Eigen::Vector3d hi =
      g2.point(g2.dims.x() - 1, g2.dims.y() - 1, g2.dims.z() - 1) + Eigen::Vector3d::Constant(0.5 * h);

  std::vector<QueryResult> results(poses.size());
  for (std::size_t n = 0; n < poses.size(); ++n) {
    const Pose& pose = poses[n];
    QueryResult& r = results[n];
    if (!pose.is_finite() || !(std::abs(pose.rotation.norm() - 1.0) < 1e-3)) {
      r.flags = query_bad_pose;
      continue;
    }
    Pose base = pose;
    base.rotation.normalize();
    // The probes: the pose, then +-step along each translation axis, then each rotation axis.
    std::vector<Pose> probes{base};
    for (int a = 0; a < 3 && options_.force; ++a)
      for (double s : {1.0, -1.0}) {
        Pose p = base;
        p.translation[a] += s * translation_step_;
        probes.push_back(p);
      }
    for (int a = 0; a < 3 && options_.torque; ++a)
      for (double s : {1.0, -1.0}) probes.push_back(turned(base, Eigen::Vector3d::Unit(a), s * rotation_step_));

    // Part 1's lattice points moved into part 2's frame, those inside part 2's box.
    std::vector<Eigen::Vector3d> q;
    std::vector<std::size_t> p_index;
    std::vector<std::size_t> probe_end;
    for (const Pose& probe : probes) {
      const Eigen::Matrix3d Rt = probe.rotation.toRotationMatrix().transpose();
      for (std::size_t i = 0; i < g1.count(); ++i) {
        if (rho1_[i] == 0.0f) continue;
        const Eigen::Vector3d x = Rt * (g1.point(i) - probe.translation);
        if ((x.array() < lo.array()).any() || (x.array() > hi.array()).any()) continue;
        q.push_back(x);
        p_index.push_back(i);
      }
      probe_end.push_back(q.size());
    }
    const DescriptorFields at_q =
        descriptors_at_points(ctx_, part2_mesh_, q, g2.origin, g2.spacing, part1_.params, options_.descriptors);
    const std::vector<float> rho2 = affinity_imaginary(at_q);
    std::vector<double> energy(probes.size(), 0.0);
    for (std::size_t k = 0, j = 0; k < probes.size(); ++k) {
      double sum = 0;
      for (; j < probe_end[k]; ++j) sum += double(rho1_[p_index[j]]) * double(rho2[j]);
      energy[k] = h3 * sum;
    }
    r.energy = energy[0];
    r.score = {-energy[0], 0.0};
    std::size_t k = 1;
    if (options_.force)
      for (int a = 0; a < 3; ++a, k += 2) r.force[a] = -(energy[k] - energy[k + 1]) / (2 * translation_step_);
    if (options_.torque)
      for (int a = 0; a < 3; ++a, k += 2) r.torque[a] = -(energy[k] - energy[k + 1]) / (2 * rotation_step_);
    r.modes = 0;
  }
  return results;
}

}  // namespace snapfit
