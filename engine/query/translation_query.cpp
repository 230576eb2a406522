#include "engine/query/translation_query.h"

#include <algorithm>

#include "engine/query/line_kernel.h"
#include "engine/query/query_launch.h"
#include "engine/query/translation_lines.h"
#include "engine/runtime/cl_values.h"
#include "engine/spectra/mode_order.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

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
    launch_ = std::make_unique<QueryLaunch>(
        ctx, spectra, variant, reach_.back(), "translation_lines", options,
        SharedQueryArgs{kLinePose, kLinePoses, kLinePoseCount, kLineGroupsPerPose, kLinePartials}, cache);
    try {
      const auto& box = lines_.weights;
      weights_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * box.size(),
                            const_cast<Complex*>(box.data()));
      extras_ = cl::Buffer(launch_->context(), CL_MEM_READ_ONLY, sizeof(ExtraMode) * (kMaxUnpairedExtras + 1));
      cl::Kernel& k = launch_->kernel();
      k.setArg(kLineWeights, weights_);
      k.setArg(kLineExtras, extras_);
      const Eigen::Vector3d inv = spectra.length.cwiseInverse();
      k.setArg(kLineInvLength, float4_of(inv));
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
      upload_line_selection(*launch_, selection_, reach_[modes - 1], records_, line_capacity_);
      if (!selection_.extras.empty())
        launch_->queue().enqueueWriteBuffer(extras_, CL_TRUE, 0, sizeof(ExtraMode) * selection_.extras.size(),
                                            selection_.extras.data());
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
