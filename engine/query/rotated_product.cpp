#include "engine/query/rotated_product.h"

#include <algorithm>

#include "engine/runtime/cl_values.h"
#include "engine/runtime/compute_context.h"
#include "engine/runtime/kernel_sources.h"
#include "engine/spectra/mode_order.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// Arguments of the rotated_product kernel (kernels/rotated_product.cl), in order.
enum RotatedProductArg : cl_uint {
  kModes = 0,     // global int4*: (box node, kx, ky, kz)
  kS1w,           // global float2*: S1(w_k) dw
  kPartners,      // global int*: the box node of -k (or -1)
  kCount,         // int
  kS2d,           // global float2*: part 2's deconvolved spectrum (FFT order)
  kDims,          // int4
  kRotation,      // float16: R0 row-major
  kBoxLength,     // float4: L
  kBoxInvLength,  // float4: 1 / L
  kProduct,       // global float8*: the box
};

}  // namespace

RotatedProduct::RotatedProduct(const ComputeContext& ctx, const PairSpectra& spectra, const TranslationLines& lines,
                               const ProgramCacheConfig& cache)
    : device_name_(ctx.device.info.name) {
  if (spectra.part2.deconvolved.empty())
    throw Error("the exact rotation needs part 2's deconvolved spectrum (SpectrumOptions::exact_rotation_width)");
  const auto& d = spectra.dims;
  const double dw = 1.0 / (spectra.length.x() * spectra.length.y() * spectra.length.z());
  box_nodes_ = std::size_t(lines.box_dims[0]) * lines.box_dims[1] * lines.box_dims[2];
  // One evaluation per conjugate pair (both parts' samples imaginary, so the product's
  // terms at w and -w are conjugates) or per unpartnered mode, in the order of the pair's
  // first rank, so the first n entries cover the first m' modes for the n with
  // covered_[n - 1] <= m'.
  const bool pairs = spectra.conjugate_pairs() == 1;
  std::vector<std::uint32_t> rank(d[0] * d[1] * d[2], std::uint32_t(-1));
  for (std::size_t i = 0; i < lines.max_modes; ++i) rank[lines.order[i]] = static_cast<std::uint32_t>(i);
  std::vector<cl_int4> modes;
  std::vector<Complex> s1w;
  std::vector<cl_int> partners;
  for (std::size_t i = 0; i < lines.max_modes; ++i) {
    const std::size_t k = lines.order[i], neg = negated_node(d, k);
    const bool paired = pairs && neg != kNoNode && neg != k;
    if (paired && rank[neg] < i) continue;  // evaluated with its partner
    const std::array<int, 3> kk = signed_node(d, k);
    modes.push_back(cl_int4{{static_cast<cl_int>(box_node(lines, kk[0], kk[1], kk[2])), kk[0], kk[1], kk[2]}});
    s1w.push_back(spectra.part1.rho[k] * static_cast<float>(dw));
    // The partner is in the box when it is among the first max_modes modes.
    partners.push_back(
        paired && rank[neg] != std::uint32_t(-1) ? static_cast<cl_int>(box_node(lines, -kk[0], -kk[1], -kk[2])) : -1);
    covered_.push_back(paired && rank[neg] != std::uint32_t(-1) ? std::max(i, std::size_t(rank[neg])) + 1 : i + 1);
  }
  // covered_[n]: the modes the first n + 1 entries hold, as a running maximum.
  for (std::size_t n = 1; n < covered_.size(); ++n) covered_[n] = std::max(covered_[n], covered_[n - 1]);
  mode_count_ = lines.max_modes;
  const EsKernel es = spectra.rotation_kernel();
  try {
    const std::string options =
        "-cl-std=CL1.2 -cl-denorms-are-zero -D ES_WIDTH=" + std::to_string(es.width) +  // as the query's
        " -D ES_BETA=" + std::to_string(es.beta) + "f";
    kernel_ =
        cl::Kernel(build_program(ctx, "rotated_product", kernel_source("rotated_product"), options, cache).program,
                   "rotated_product");
    modes_ =
        cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_int4) * modes.size(), modes.data());
    s1w_ = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * s1w.size(), s1w.data());
    partners_ = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_int) * partners.size(),
                           partners.data());
    const std::vector<Complex>& s2d = spectra.part2.deconvolved;
    s2d_ = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(Complex) * s2d.size(),
                      const_cast<Complex*>(s2d.data()));
    kernel_.setArg(kModes, modes_);
    kernel_.setArg(kS1w, s1w_);
    kernel_.setArg(kPartners, partners_);
    kernel_.setArg(kS2d, s2d_);
    kernel_.setArg(kDims, cl_int4{{int(d[0]), int(d[1]), int(d[2]), 0}});
    kernel_.setArg(kBoxLength, float4_of(spectra.length));
    kernel_.setArg(kBoxInvLength, float4_of(spectra.length.cwiseInverse()));
  } catch (const cl::Error& e) {
    throw_device_error("cannot set up the exact rotation", device_name_, e);
  }
}

void RotatedProduct::compute(cl::CommandQueue& queue, const Eigen::Matrix3d& R0, std::size_t modes,
                             const cl::Buffer& box) {
  // The entries whose first rank is below m' (their partners may lie beyond it: harmless).
  std::size_t count = 0;
  if (modes > 0) {
    const std::size_t m = std::min(modes, mode_count_);
    count = covered_.size();
    // The fewest entries that hold the first m modes.
    count = static_cast<std::size_t>(std::lower_bound(covered_.begin(), covered_.end(), m) - covered_.begin()) + 1;
    count = std::min(count, covered_.size());
  }
  if (count == 0) return;
  cl_float16 rotation{};
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) rotation.s[3 * r + c] = static_cast<float>(R0(r, c));
  try {
    kernel_.setArg(kCount, static_cast<cl_int>(count));
    kernel_.setArg(kRotation, rotation);
    kernel_.setArg(kProduct, box);
    const std::size_t group = 64;
    queue.enqueueNDRangeKernel(kernel_, cl::NullRange, cl::NDRange((count + group - 1) / group * group),
                               cl::NDRange(group));
    queue.finish();
  } catch (const cl::Error& e) {
    throw_device_error("exact rotation failed", device_name_, e);
  }
}

}  // namespace snapfit
