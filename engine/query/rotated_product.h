#pragma once
// The product spectrum of the pair with part 2 turned by R0, exact in rotation
// (kernels/rotated_product.cl; docs/design.md "Exact rotation"): for the first m modes
// of the mode order, W0_k = S1(w_k) S2(-R0^T w_k) dw and its rotation derivative
// D_k = S1(w_k) dw (w_k x R0 grad S2(-R0^T w_k)), with S2 and its gradient evaluated by
// the kernel of part 2's deconvolved spectrum (engine/spectra/es_kernel.h), written into the
// product box of a TranslationLines (engine/query/translation_lines.h) as float8 per node.
// The x-line sums of engine/query/rotated_product_query.h read it.
#include <CL/opencl.hpp>
#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "engine/query/translation_lines.h"

namespace snapfit {

class RotatedProduct {
 public:
  // Uploads part 2's deconvolved spectrum and, for the first lines.max_modes modes,
  // their box nodes and S1(w_k) dw. Throws snapfit::Error when the spectra have no
  // deconvolved spectrum (SpectrumOptions::exact_rotation_width) or the device fails.
  RotatedProduct(const ComputeContext& ctx, const PairSpectra& spectra, const TranslationLines& lines,
                 const ProgramCacheConfig& cache = default_program_cache());

  // Bytes of one product box (float8 per node).
  std::size_t box_bytes() const { return box_nodes_ * 8 * sizeof(float); }
  // Enqueues the product for the first `modes` modes into `box` on `queue` and waits
  // for it. Not thread-safe: one caller at a time.
  void compute(cl::CommandQueue& queue, const Eigen::Matrix3d& R0, std::size_t modes, const cl::Buffer& box);

 private:
  cl::Kernel kernel_;
  cl::Buffer modes_, s1w_, partners_, s2d_;
  std::size_t mode_count_ = 0, box_nodes_ = 0;
  std::vector<std::size_t> covered_;  // modes held by the first n + 1 entries (ascending)
  std::string device_name_;
};

}  // namespace snapfit
