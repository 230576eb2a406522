#include "engine/translation_query.h"

#include <algorithm>

#include "engine/mode_order.h"
#include "engine/query_launch.h"
#include "engine/translation_lines.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Arguments of the translation_lines kernel (kernels/pose_query.cl), in order.
enum TranslationLinesArg : cl_uint {
  kWeights = 0,    // global float2*: W_k in the dense box of x-lines
  kLines,          // global int4*: the selected lines (engine/translation_lines.h LineRecord)
  kExtras,         // global float4*: the extra single terms (ExtraMode)
  kExtraCount,     // int
  kFolded,         // int: 1 when the lines are one half of the box (a real correlation)
  kPose,           // float16
  kPoses,          // global float16*
  kPoseCount,      // int
  kLineCount,      // int
  kGroupsPerPose,  // int
  kTableHalf,      // int
  kPartials,       // global float*
  kInvLength,      // float4: 1 / L
};

class TranslationQuery final : public QueryEngine {
 public:
  TranslationQuery(const ComputeContext& ctx, const PairSpectra& spectra, QueryVariant variant,
                   const ProgramCacheConfig& cache)
      : variant_(variant) {
    if (variant.torque) throw Error("a translation-only query has no torque");
    const std::vector<std::size_t> order = mode_order(spectra);
    reach_ = mode_reach(spectra.dims, order);
    lines_ = build_translation_lines(spectra, order, variant.fold_conjugate_pairs);
    std::string options = " -D TRANSLATION_ONLY";
    if (variant.force) options += " -D FORCE";
    launch_ =
        std::make_unique<QueryLaunch>(ctx, spectra, variant, reach_.back(), "translation_lines", options,
                                      SharedQueryArgs{kPose, kPoses, kPoseCount, kGroupsPerPose, kPartials}, cache);
    try {
      const auto& box = lines_.weights;
      weights_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * box.size(),
                            const_cast<Complex*>(box.data()));
      extras_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY, sizeof(ExtraMode) * (kMaxUnpairedExtras + 1));
      cl::Kernel& k = launch_->kernel();
      k.setArg(kWeights, weights_);
      k.setArg(kExtras, extras_);
      const Eigen::Vector3d inv = spectra.length.cwiseInverse();
      k.setArg(kInvLength, cl_float4{{float(inv.x()), float(inv.y()), float(inv.z()), 0.0f}});
    } catch (const cl::Error& e) {
      throw Error("cannot set up translation queries on " + launch_->device_name() + ": " + e.what() + " (error " +
                  std::to_string(e.err()) + ")");
    }
    select(order.size());
  }

  const QueryVariant& variant() const override { return variant_; }
  std::size_t max_modes() const override { return reach_.size(); }
  std::size_t modes() const override { return selection_.modes; }
  // The nodes of the selected line intervals (folded: one per pair) and the extra terms.
  std::size_t evaluated_terms() const override { return selection_.nodes + selection_.extras.size(); }

  void set_modes(std::size_t m) override {
    const std::size_t clamped = std::clamp<std::size_t>(m, 1, max_modes());
    if (clamped != selection_.modes) select(clamped);
  }

  QueryResult query(const Pose& pose) override {
    QueryResult result;
    launch_->evaluate(&pose, 1, &result);
    return result;
  }
  using QueryEngine::query_batch;
  void query_batch(const Pose* poses, std::size_t count, QueryResult* results) override {
    launch_->evaluate(poses, count, results);
  }

 private:
  // Selects and uploads the lines and extras that sum exactly the first m' modes.
  void select(std::size_t modes) {
    select_lines(lines_, modes, selection_);
    try {
      cl::Kernel& k = launch_->kernel();
      const std::size_t n = std::max<std::size_t>(selection_.lines.size(), 1);
      if (n > line_capacity_) {
        line_capacity_ = std::max(n + n / 4, std::size_t(64));
        records_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY, sizeof(LineRecord) * line_capacity_);
        k.setArg(kLines, records_);
      }
      // Blocking: the host vectors change with the next set_modes.
      cl::CommandQueue& queue = launch_->queue();
      if (!selection_.lines.empty())
        queue.enqueueWriteBuffer(records_, CL_TRUE, 0, sizeof(LineRecord) * selection_.lines.size(),
                                 selection_.lines.data());
      if (!selection_.extras.empty())
        queue.enqueueWriteBuffer(extras_, CL_TRUE, 0, sizeof(ExtraMode) * selection_.extras.size(),
                                 selection_.extras.data());
      k.setArg(kExtraCount, static_cast<cl_int>(selection_.extras.size()));
      k.setArg(kFolded, static_cast<cl_int>(selection_.folded ? 1 : 0));
      k.setArg(kLineCount, static_cast<cl_int>(selection_.lines.size()));
      k.setArg(kTableHalf, static_cast<cl_int>(reach_[modes - 1]));
    } catch (const cl::Error& e) {
      throw Error("cannot change m' on " + launch_->device_name() + ": " + e.what() + " (error " +
                  std::to_string(e.err()) + ")");
    }
    launch_->set_work(selection_.nodes, modes);
  }

  QueryVariant variant_;
  std::vector<int> reach_;  // max |k| of the modes [0, i]: the phase tables' reach
  TranslationLines lines_;
  LineSelection selection_;
  std::unique_ptr<QueryLaunch> launch_;
  cl::Buffer weights_, records_, extras_;
  std::size_t line_capacity_ = 0;
};

}  // namespace

std::unique_ptr<QueryEngine> make_translation_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                                    const QueryVariant& variant, const ProgramCacheConfig& cache) {
  return std::make_unique<TranslationQuery>(ctx, spectra, variant, cache);
}

}  // namespace snapfit
