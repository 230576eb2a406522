#pragma once
// The exact-rotation 6-DOF query (docs/design.md "Exact rotation"): the pair's product
// spectrum made for a rotation R0 of part 2 (engine/query/rotated_product.h), with its rotation
// derivative, summed along x-lines (kernels/pose_query.cl rotated_lines) at any pose
// R = exp([dtheta]x) R0 to first order in dtheta:
//   f(R, t) = sum_k (W0_k + dtheta . D_k) e^{2 pi i w_k.tau},  tau = t + R c2 - c1,
//   E = -Re f,  F = -dE/dt,  T = -dE/dtheta = J_l(dtheta)^-T Re sum_k D_k e^{i phi} + (R c2) x F,
// the torque the exact derivative of that energy (J_l the left Jacobian of SO(3)), so E,
// F and T are consistent by construction and exact at R0. R0 follows the queried poses
// (QueryVariant::product_update): before each query whose rotation differs, or on a worker
// thread that predicts the next rotation from the last two queried.
#include <memory>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/program_cache.h"
#include "engine/spectra/spectra.h"
#include "snapfit/query.h"

namespace snapfit {

// Throws snapfit::Error for a translation-only variant, spectra without a deconvolved
// part 2 (SpectrumOptions::exact_rotation_width), or a device failure.
std::unique_ptr<QueryEngine> make_rotated_product_query(const ComputeContext& ctx, const PairSpectra& spectra,
                                                        const QueryVariant& variant,
                                                        const ProgramCacheConfig& cache = default_program_cache());

}  // namespace snapfit
