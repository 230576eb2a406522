#pragma once
// What the two query kernels of kernels/pose_query.cl share (engine/query/six_dof_query.h,
// engine/query/translation_query.h): the frame a pose is placed in, the program and launch
// shape, the pose and partial-sum buffers, and the partial sums read back and added
// per pose. The owner sets its m'-dependent kernel arguments in set_modes and calls
// set_work; evaluate() then allocates nothing for batches no larger than any before:
// a single query is one kernel argument, one launch and one blocking read into memory
// held since set-up.
#include <CL/opencl.hpp>
#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

// Both parts' centred boxes (engine/spectra/spectra.h) and the periodic box L.
struct PoseFrame {
  Eigen::Vector3d c1, c2, half1, half2, length;

  explicit PoseFrame(const PairSpectra& spectra);
  // The kernel's pose for part 2 at `pose`: R row-major, then tau / L as a float pair
  // (hi + lo), tau = t + R c2 - c1 the offset between the centred boxes. Returns
  // query_bad_pose for a non-finite or non-unit rotation (or, with `identity_only`, any
  // rotation but the identity), query_outside_grid when part 2's box reaches an image of
  // part 1's box (the periodic sum would alias), else query_ok.
  std::uint32_t place(const Pose& pose, bool identity_only, Eigen::Matrix3d& R, cl_float16& packed) const;
};

// The sums a kernel's work-group returns (kernels/pose_query.cl SUMS_PER_GROUP): the 8
// outputs (Re f, Im f, F, T in part 2's frame) of the total, then of the bands
// (m'/4, m'/2] and (m'/2, m'] for the error estimate (engine/query/error_estimate.h).
constexpr std::size_t kSumsPerGroup = 24;

// The per-pose sums of one of them, added over the work-groups, into a result: E = -Re f,
// F, and T rotated by R.
void fill_result(const double sums[8], const Eigen::Matrix3d& R, const QueryVariant& variant, QueryResult& result);

// What a strategy adds to the shared launch (all optional): how a placed pose becomes the
// kernel's pose, and how the kernel's sums become a result. Called on the querying
// thread, once per pose; they must not allocate.
class QueryHooks {
 public:
  virtual ~QueryHooks() = default;
  // The pose as place() packed it (R row-major, tau / L), for R.
  virtual void encode(const Eigen::Matrix3d& /*R*/, cl_float16& /*packed*/) const {}
  // Default: fill_result.
  virtual void finish(const double sums[8], const Eigen::Matrix3d& R, const QueryVariant& variant,
                      QueryResult& result) const;
};

// The numbers of the kernel arguments QueryLaunch sets itself.
struct SharedQueryArgs {
  cl_uint pose;             // float16: the pose of a single query
  cl_uint poses;            // global float16*: the poses of a batch
  cl_uint pose_count;       // int
  cl_uint groups_per_pose;  // int
  cl_uint partials;         // global float*: kSumsPerGroup sums per work-group
};

class QueryLaunch {
 public:
  // Builds `kernel_name` from kernels/spectrum_sample.cl + pose_query.cl with `options`
  // plus WG_SIZE and MAX_HALF = `reach` (the largest |k| on any axis of any mode).
  // Launch shape: 64 work-items, one group per 64 units of work, up to 2 groups per
  // compute unit (on PoCL's CPU device 1-256 work-items and 1-4 groups per pose measured
  // alike at m' = 32,768: a work-group runs as a loop on one core); SNAPFIT_QUERY_WG,
  // _GROUPS and _MODES_PER_GROUP override them for measurements on other devices.
  // Throws snapfit::Error naming the device when the phase tables do not fit its local
  // memory or the set-up fails.
  QueryLaunch(const ComputeContext& ctx, const PairSpectra& spectra, const QueryVariant& variant, int reach,
              const std::string& kernel_name, const std::string& options, const SharedQueryArgs& args,
              const ProgramCacheConfig& cache, const QueryHooks* hooks = nullptr);

  cl::Kernel& kernel() { return kernel_; }
  const cl::Context& context() const { return ctx_.context; }
  cl::CommandQueue& queue() { return queue_; }
  const std::string& device_name() const { return ctx_.device.info.name; }

  // After the owner's m' changed: `work` units (6-DOF records or translation-only line
  // nodes) per pose decide the groups per pose; `modes` is reported in the results.
  void set_work(std::size_t work, std::size_t modes);

  // Queries `count` poses into results[0 .. count).
  void evaluate(const Pose* poses, std::size_t count, QueryResult* results);

 private:
  void reserve(std::size_t poses);

  ComputeContext ctx_;
  PoseFrame frame_;
  QueryVariant variant_;
  SharedQueryArgs args_;
  const QueryHooks* hooks_;
  QueryHooks default_hooks_;
  // The engine's own in-order queue without profiling: a query is one kernel launch and
  // one small blocking read, not queued behind other stages' work on ctx.queue.
  cl::CommandQueue queue_;
  cl::Kernel kernel_;
  std::size_t wg_ = 64, max_groups_ = 4, work_per_group_ = 64;
  std::size_t groups_per_pose_ = 1, modes_ = 0;
  cl::Buffer poses_, partials_;
  std::size_t pose_capacity_ = 0;
  // Host scratch for a batch, grown with the pose buffer.
  std::vector<float> partial_host_;
  std::vector<cl_float16> packed_;
  std::vector<Eigen::Matrix3d> rotations_;
  std::vector<std::size_t> slot_;
};

}  // namespace snapfit
