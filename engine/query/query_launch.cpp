#include "engine/query/query_launch.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>

#include "engine/query/error_estimate.h"
#include "engine/runtime/kernel_sources.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

std::size_t env_size(const char* name, std::size_t fallback) {
  const char* v = std::getenv(name);
  return v && *v ? static_cast<std::size_t>(std::strtoul(v, nullptr, 10)) : fallback;
}

Error device_error(const std::string& what, const std::string& device, const cl::Error& e) {
  return Error(what + " on " + device + ": " + e.what() + " (error " + std::to_string(e.err()) + ")");
}

}  // namespace

PoseFrame::PoseFrame(const PairSpectra& spectra)
    : c1(spectra.part1.centre),
      c2(spectra.part2.centre),
      half1(spectra.part1.half_extent),
      half2(spectra.part2.half_extent),
      length(spectra.length) {}

std::uint32_t PoseFrame::place(const Pose& pose, bool identity_only, Eigen::Matrix3d& R, cl_float16& packed) const {
  if (!pose.is_finite()) return query_bad_pose;
  const double norm = pose.rotation.norm();
  if (!(std::abs(norm - 1.0) < 1e-3)) return query_bad_pose;  // not a rotation: refuse rather than guess
  R = pose.rotation.normalized().toRotationMatrix();
  if (identity_only && !R.isIdentity(1e-6)) return query_bad_pose;
  const Eigen::Vector3d tau = pose.translation + R * c2 - c1;
  const Eigen::Vector3d reach = half1 + R.cwiseAbs() * half2;
  if (((tau.cwiseAbs() + reach).array() > length.array()).any()) return query_outside_grid;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) packed.s[3 * r + c] = static_cast<float>(R(r, c));
  for (int a = 0; a < 3; ++a) {
    const double x = tau[a] / length[a];
    packed.s[9 + a] = static_cast<float>(x);
    packed.s[12 + a] = static_cast<float>(x - double(packed.s[9 + a]));
  }
  packed.s[15] = 0.0f;
  return query_ok;
}

QueryLaunch::QueryLaunch(const ComputeContext& ctx, const PairSpectra& spectra, const QueryVariant& variant, int reach,
                         const std::string& kernel_name, const std::string& options, const SharedQueryArgs& args,
                         const ProgramCacheConfig& cache, const QueryHooks* hooks)
    : ctx_(ctx), frame_(spectra), variant_(variant), args_(args), hooks_(hooks ? hooks : &default_hooks_) {
  const DeviceInfo& info = ctx.device.info;
  wg_ = 1;
  while (wg_ * 2 <= std::min<std::size_t>(env_size("SNAPFIT_QUERY_WG", 64), info.max_work_group_size)) wg_ *= 2;
  max_groups_ =
      std::max<std::size_t>(1, env_size("SNAPFIT_QUERY_GROUPS", std::max<std::size_t>(2, 2 * info.compute_units)));
  work_per_group_ = std::max<std::size_t>(1, env_size("SNAPFIT_QUERY_MODES_PER_GROUP", wg_));
  // Phase tables for |k| <= reach (+ 8 for the translation lines' last chunk) on every
  // axis, and the reduction scratch, in local memory.
  const std::size_t local_bytes =
      3 * (2 * std::size_t(reach) + 17) * sizeof(Complex) + kSumsPerGroup * sizeof(float) * wg_;
  if (local_bytes > info.local_memory_bytes) {
    const auto& d = spectra.dims;
    throw Error("FFT grid of " + std::to_string(d[0]) + "x" + std::to_string(d[1]) + "x" + std::to_string(d[2]) +
                " needs " + std::to_string(local_bytes) +
                " bytes of local memory for the query kernel's phase tables; " + info.name + " has " +
                std::to_string(info.local_memory_bytes));
  }
  try {
    queue_ = cl::CommandQueue(ctx.context, ctx.device.device, 0);
    // Subnormals flushed: a pose at rest at the fit has offsets whose products fall below
    // float's smallest normal, and the slow path for them would lengthen the frame several
    // times (core/subnormal_flush.h; PoCL sets its flush bits around a kernel from this option).
    const std::string all = "-cl-std=CL1.2 -cl-denorms-are-zero -D WG_SIZE=" + std::to_string(wg_) +
                            " -D MAX_HALF=" + std::to_string(reach) + options;
    kernel_ = cl::Kernel(
        build_program(ctx, "pose_query", kernel_source("spectrum_sample") + kernel_source("pose_query"), all, cache)
            .program,
        kernel_name.c_str());
    kernel_.setArg(args_.pose, cl_float16{});
    reserve(16);
  } catch (const cl::Error& e) {
    throw device_error("cannot set up pose queries", info.name, e);
  }
}

void QueryLaunch::reserve(std::size_t poses) {
  if (poses <= pose_capacity_) return;
  pose_capacity_ = std::max(poses, 2 * pose_capacity_);
  poses_ = cl::Buffer(ctx_.context, CL_MEM_READ_ONLY, sizeof(cl_float16) * pose_capacity_);
  partials_ = cl::Buffer(ctx_.context, CL_MEM_WRITE_ONLY, sizeof(float) * kSumsPerGroup * pose_capacity_ * max_groups_);
  kernel_.setArg(args_.poses, poses_);
  kernel_.setArg(args_.partials, partials_);
  partial_host_.resize(kSumsPerGroup * pose_capacity_ * max_groups_);
  packed_.resize(pose_capacity_);
  rotations_.resize(pose_capacity_);
  slot_.resize(pose_capacity_);
}

void QueryLaunch::set_work(std::size_t work, std::size_t modes) {
  groups_per_pose_ = std::clamp<std::size_t>((work + work_per_group_ - 1) / work_per_group_, 1, max_groups_);
  modes_ = modes;
  kernel_.setArg(args_.groups_per_pose, static_cast<cl_int>(groups_per_pose_));
}

void fill_result(const double sums[8], const Eigen::Matrix3d& R, const QueryVariant& variant, QueryResult& result) {
  result.score = {sums[0], sums[1]};
  result.energy = -sums[0];  // E = -Re f
  if (variant.force) result.force = Eigen::Vector3d(sums[2], sums[3], sums[4]);
  if (variant.torque) result.torque = R * Eigen::Vector3d(sums[5], sums[6], sums[7]);  // to part 1's frame
}

void QueryHooks::finish(const double sums[8], const Eigen::Matrix3d& R, const QueryVariant& variant,
                        QueryResult& result) const {
  fill_result(sums, R, variant, result);
}

void QueryLaunch::evaluate(const Pose* poses, std::size_t count, QueryResult* results) {
  const auto start = std::chrono::steady_clock::now();
  try {
    reserve(count);
    std::size_t sent = 0;
    for (std::size_t i = 0; i < count; ++i) {
      results[i] = QueryResult{};
      results[i].modes = modes_;
      results[i].flags = frame_.place(poses[i], variant_.translation_only, rotations_[sent], packed_[sent]);
      if (results[i].flags != query_ok) continue;
      hooks_->encode(rotations_[sent], packed_[sent]);
      slot_[sent++] = i;
    }
    if (sent > 0) {
      if (sent == 1) {
        kernel_.setArg(args_.pose, packed_[0]);  // one pose: an argument, no buffer write
      } else {
        queue_.enqueueWriteBuffer(poses_, CL_FALSE, 0, sizeof(cl_float16) * sent, packed_.data());
      }
      kernel_.setArg(args_.pose_count, static_cast<cl_int>(sent));
      const std::size_t groups = groups_per_pose_ * sent;
      queue_.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange(groups * wg_), cl::NDRange(wg_));
      queue_.enqueueReadBuffer(partials_, CL_TRUE, 0, sizeof(float) * kSumsPerGroup * groups, partial_host_.data());
      for (std::size_t s = 0; s < sent; ++s) {
        // The total, band (m'/4, m'/2] and band (m'/2, m'], each 8 sums.
        double sums[kSumsPerGroup] = {};
        for (std::size_t g = 0; g < groups_per_pose_; ++g)
          for (std::size_t j = 0; j < kSumsPerGroup; ++j)
            sums[j] += partial_host_[kSumsPerGroup * (s * groups_per_pose_ + g) + j];
        QueryResult& result = results[slot_[s]];
        QueryResult band_a, band_b;
        hooks_->finish(sums, rotations_[s], variant_, result);
        hooks_->finish(sums + 8, rotations_[s], variant_, band_a);
        hooks_->finish(sums + 16, rotations_[s], variant_, band_b);
        result.error_estimate = estimate_error(band_a, band_b);
      }
    }
  } catch (const cl::Error& e) {
    throw device_error("pose query failed", ctx_.device.info.name, e);
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (std::size_t i = 0; i < count; ++i) results[i].seconds = seconds / double(std::max<std::size_t>(1, count));
}

}  // namespace snapfit
