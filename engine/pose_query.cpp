#include "engine/pose_query.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "engine/error.h"
#include "engine/kernel_sources.h"

namespace snapfit {

struct PoseQueryEngine::Impl {
  Impl(const ComputeContext& c, QueryVariant v) : ctx(c), variant(v) {}
  const ComputeContext& ctx;
  QueryVariant variant;
  Eigen::Vector3d c1, c2, half1, half2, length;
  std::size_t mode_total = 0, mode_count = 0;
  std::size_t wg = 64, max_groups = 4;
  cl::Buffer modes, weights, s2, sq[3], poses, partials;
  std::size_t pose_capacity = 0, partial_capacity = 0;
  cl::Kernel kernel;

  void ensure_capacity(std::size_t pose_count, std::size_t groups) {
    if (pose_count > pose_capacity) {
      pose_capacity = std::max<std::size_t>(pose_count, 16);
      poses = cl::Buffer(ctx.context, CL_MEM_READ_ONLY, sizeof(float) * 12 * pose_capacity);
    }
    if (groups > partial_capacity) {
      partial_capacity = std::max<std::size_t>(groups, 64);
      partials = cl::Buffer(ctx.context, CL_MEM_WRITE_ONLY, sizeof(float) * 8 * partial_capacity);
    }
  }
};

namespace {

// Rotation matrix of a unit quaternion, or false when the pose is unusable.
bool checked_rotation(const Pose& pose, Eigen::Matrix3d& R) {
  if (!pose.is_finite()) return false;
  const double norm = pose.rotation.norm();
  if (!(std::abs(norm - 1.0) < 1e-3)) return false;  // not a rotation: refuse rather than guess
  R = pose.rotation.normalized().toRotationMatrix();
  return true;
}

}  // namespace

PoseQueryEngine::PoseQueryEngine(const ComputeContext& ctx, const PairSpectra& spectra, QueryVariant variant,
                                 const ProgramCacheConfig& cache)
    : impl_(std::make_unique<Impl>(ctx, variant)) {
  Impl& m = *impl_;
  if (variant.torque && !spectra.torque) throw Error("the query variant needs torque, but the spectra have no torque terms");
  if (variant.torque && variant.translation_only) throw Error("a translation-only query has no torque");
  m.c1 = spectra.part1.centre;
  m.c2 = spectra.part2.centre;
  m.half1 = spectra.part1.half_extent;
  m.half2 = spectra.part2.half_extent;
  m.length = spectra.length;
  const auto& dims = spectra.dims;
  const std::size_t total = dims[0] * dims[1] * dims[2];

  // Every node, by increasing |w| (the low-pass ball grows with m').
  std::vector<Eigen::Vector3f> w(total);
  std::vector<float> norm2(total);
  for (std::size_t z = 0; z < dims[2]; ++z)
    for (std::size_t y = 0; y < dims[1]; ++y)
      for (std::size_t x = 0; x < dims[0]; ++x) {
        const std::size_t k = x + dims[0] * (y + dims[1] * z);
        w[k] = Eigen::Vector3f(float(spectra.frequency(0, x)), float(spectra.frequency(1, y)), float(spectra.frequency(2, z)));
        norm2[k] = w[k].squaredNorm();
      }
  std::vector<std::size_t> order(total);
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return norm2[a] < norm2[b]; });

  // dw = 1 / (L_x L_y L_z) (DESIGN.md), folded into the weights.
  const double dw = 1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z());
  std::vector<cl_float4> mode_data(total);
  std::vector<Complex> weight_data(total);
  for (std::size_t i = 0; i < total; ++i) {
    const std::size_t k = order[i];
    mode_data[i] = cl_float4{{w[k].x(), w[k].y(), w[k].z(), 0.0f}};
    Complex weight = spectra.part1.rho[k] * static_cast<float>(dw);
    if (variant.translation_only) {
      // rho2^(-w_k) at the node -k: S2(-w) e^{-2 pi i (-w).c2} folds into the phase tau.
      const std::size_t x = k % dims[0], y = (k / dims[0]) % dims[1], z = k / (dims[0] * dims[1]);
      const std::size_t neg = (dims[0] - x) % dims[0] + dims[0] * ((dims[1] - y) % dims[1] + dims[1] * ((dims[2] - z) % dims[2]));
      weight *= spectra.part2.rho[neg];
    }
    weight_data[i] = weight;
  }
  m.mode_total = total;
  m.mode_count = total;

  try {
    m.modes = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * total, mode_data.data());
    m.weights = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * total, weight_data.data());
    auto upload = [&](const std::vector<Complex>& v) {
      return cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * v.size(),
                        const_cast<Complex*>(v.data()));
    };
    // Unused spectrum arguments get a small placeholder buffer (OpenCL needs a valid one).
    const std::vector<Complex> none(1);
    m.s2 = variant.translation_only ? upload(none) : upload(spectra.part2.rho);
    for (int a = 0; a < 3; ++a) m.sq[a] = variant.torque ? upload(spectra.part2.moments[a]) : upload(none);

    m.wg = 1;
    while (m.wg * 2 <= std::min<std::size_t>(64, ctx.device.info.max_work_group_size)) m.wg *= 2;
    m.max_groups = std::max<std::size_t>(2, 2 * ctx.device.info.compute_units);
    std::string options = "-cl-std=CL1.2 -D WG_SIZE=" + std::to_string(m.wg);
    if (variant.force) options += " -D FORCE";
    if (variant.torque) options += " -D TORQUE";
    if (variant.translation_only) options += " -D TRANSLATION_ONLY";
    if (!variant.translation_only && variant.interpolation == Interpolation::tricubic) options += " -D TRICUBIC";
    m.kernel = cl::Kernel(build_program(ctx, "pose_query", kernel_source("spectrum_sample") + kernel_source("pose_query"), options, cache).program, "pose_query");
    m.kernel.setArg(0, m.modes);
    m.kernel.setArg(1, m.weights);
    m.kernel.setArg(2, m.s2);
    m.kernel.setArg(3, m.sq[0]);
    m.kernel.setArg(4, m.sq[1]);
    m.kernel.setArg(5, m.sq[2]);
    m.kernel.setArg(6, cl_int4{{int(dims[0]), int(dims[1]), int(dims[2]), 0}});
    m.kernel.setArg(7, cl_float4{{float(spectra.length.x()), float(spectra.length.y()), float(spectra.length.z()), 0.0f}});
    m.ensure_capacity(1, m.max_groups);
  } catch (const cl::Error& e) {
    throw Error("cannot set up pose queries on " + ctx.device.info.name + ": " + e.what() + " (error " +
                std::to_string(e.err()) + ")");
  }
}

PoseQueryEngine::~PoseQueryEngine() = default;

std::size_t PoseQueryEngine::max_modes() const { return impl_->mode_total; }
std::size_t PoseQueryEngine::modes() const { return impl_->mode_count; }
void PoseQueryEngine::set_modes(std::size_t m) { impl_->mode_count = std::clamp<std::size_t>(m, 1, impl_->mode_total); }

QueryResult PoseQueryEngine::query(const Pose& pose) { return query_batch({pose}).front(); }

std::vector<QueryResult> PoseQueryEngine::query_batch(const std::vector<Pose>& poses) {
  Impl& m = *impl_;
  const auto start = std::chrono::steady_clock::now();
  std::vector<QueryResult> results(poses.size());
  std::vector<float> packed;
  std::vector<std::size_t> slot;  // poses sent to the device, by index
  std::vector<Eigen::Matrix3d> rotations;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    results[i].modes = m.mode_count;
    Eigen::Matrix3d R;
    if (!checked_rotation(poses[i], R) || (m.variant.translation_only && !R.isIdentity(1e-6))) {
      results[i].flags |= query_bad_pose;
      continue;
    }
    // tau = t + R c2 - c1: the offset between the two centred boxes.
    const Eigen::Vector3d tau = poses[i].translation + R * m.c2 - m.c1;
    // The periodic sum aliases once part 2's box reaches an image of part 1's box.
    const Eigen::Vector3d reach = m.half1 + R.cwiseAbs() * m.half2;
    if (((tau.cwiseAbs() + reach).array() > m.length.array()).any()) {
      results[i].flags |= query_outside_grid;
      continue;
    }
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) packed.push_back(static_cast<float>(R(r, c)));
    for (int a = 0; a < 3; ++a) packed.push_back(static_cast<float>(tau[a]));
    slot.push_back(i);
    rotations.push_back(R);
  }
  if (!slot.empty()) {
    const std::size_t groups_per_pose = std::clamp<std::size_t>((m.mode_count + m.wg - 1) / m.wg, 1, m.max_groups);
    const std::size_t groups = groups_per_pose * slot.size();
    try {
      m.ensure_capacity(slot.size(), groups);
      m.ctx.queue.enqueueWriteBuffer(m.poses, CL_FALSE, 0, sizeof(float) * packed.size(), packed.data());
      m.kernel.setArg(8, m.poses);
      m.kernel.setArg(9, static_cast<cl_int>(m.mode_count));
      m.kernel.setArg(10, static_cast<cl_int>(groups_per_pose));
      m.kernel.setArg(11, m.partials);
      m.ctx.queue.enqueueNDRangeKernel(m.kernel, cl::NullRange, cl::NDRange(groups * m.wg), cl::NDRange(m.wg));
      std::vector<float> partial(8 * groups);
      m.ctx.queue.enqueueReadBuffer(m.partials, CL_TRUE, 0, sizeof(float) * partial.size(), partial.data());
      for (std::size_t s = 0; s < slot.size(); ++s) {
        double sum[8] = {0, 0, 0, 0, 0, 0, 0, 0};
        for (std::size_t g = 0; g < groups_per_pose; ++g)
          for (int j = 0; j < 8; ++j) sum[j] += partial[8 * (s * groups_per_pose + g) + j];
        QueryResult& r = results[slot[s]];
        r.score = {sum[0], sum[1]};
        r.energy = -sum[0];  // E = -Re f
        if (m.variant.force) r.force = Eigen::Vector3d(sum[2], sum[3], sum[4]);
        if (m.variant.torque) r.torque = rotations[s] * Eigen::Vector3d(sum[5], sum[6], sum[7]);  // to part 1's frame
      }
    } catch (const cl::Error& e) {
      throw Error("pose query failed on " + m.ctx.device.info.name + ": " + e.what() + " (error " +
                  std::to_string(e.err()) + ")");
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (QueryResult& r : results) r.seconds = seconds / std::max<std::size_t>(1, poses.size());
  return results;
}

}  // namespace snapfit
