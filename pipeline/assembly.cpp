// include/snapfit/assembly.h: the public face of the pipeline (pipeline/assembly_pair.h).
#include "snapfit/assembly.h"

#include "core/progress.h"
#include "engine/query/query_engine.h"
#include "engine/runtime/device.h"
#include "pipeline/assembly_access.h"
#include "pipeline/assembly_pair.h"

namespace snapfit {

struct Assembly::State {
  ComputeContext ctx;
  AssemblyPair pair;
};

Assembly::Assembly(const Scene& scene, const AssemblyOptions& options) {
  ComputeContext ctx = make_compute_context(select_device(device_spec_from(options.device)));
  PairOptions pair_options;
  pair_options.use_cache = options.use_cache;
  pair_options.spectrum.oversampling = options.oversampling;
  pair_options.note = options.note;
  pair_options.near_field = options.near_field;
  if (options.progress) pair_options.descriptors.progress = pass_progress_bars();
  const FftLibrary fft;  // clFFT's library state, only while the spectra are computed
  AssemblyPair pair = build_assembly_pair(scene, ctx, fft, pair_options);
  state_ = std::make_unique<State>(State{std::move(ctx), std::move(pair)});
}

Assembly::~Assembly() = default;
Assembly::Assembly(Assembly&&) noexcept = default;
Assembly& Assembly::operator=(Assembly&&) noexcept = default;

const Scene& Assembly::scene() const { return state_->pair.scene; }
std::string Assembly::device_name() const { return state_->ctx.device.info.name; }
double Assembly::spacing() const { return state_->pair.grids.spacing; }
std::array<std::size_t, 3> Assembly::fft_dims() const { return state_->pair.spectra.dims; }
const AssemblyPair& AssemblyAccess::pair(const Assembly& assembly) { return assembly.state_->pair; }
const ComputeContext& AssemblyAccess::context(const Assembly& assembly) { return assembly.state_->ctx; }

QueryVariant Assembly::query_variant(Interpolation interpolation) const {
  return query_variant_for(state_->pair.scene, interpolation);
}

std::unique_ptr<QueryEngine> Assembly::make_query_engine(const QueryVariant& variant) const {
  return snapfit::make_query_engine(state_->ctx, state_->pair.spectra, variant);
}

}  // namespace snapfit
