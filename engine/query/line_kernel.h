#pragma once
// What the two x-line kernels share (kernels/pose_query.cl translation_lines and
// rotated_lines): their arguments, in one order, and the upload of a line selection
// (engine/query/translation_lines.h). They differ in the element types of the weights
// (float2 W_k, or float8 W0_k and D_k) and of the extras.
#include <CL/opencl.hpp>
#include <cstddef>

#include "engine/query/query_launch.h"
#include "engine/query/translation_lines.h"

namespace snapfit {

enum LineKernelArg : cl_uint {
  kLineWeights = 0,    // global: the dense box of x-lines (float2 W_k, or float8 W0_k, D_k)
  kLineRecords,        // global int8*: the selected lines (LineRecord)
  kLineExtras,         // global: the extra single terms
  kLineExtraCount,     // int
  kLineFolded,         // int: 1 when the lines are one half of the box (a real correlation)
  kLinePose,           // float16
  kLinePoses,          // global float16*
  kLinePoseCount,      // int
  kLineCount,          // int
  kLineGroupsPerPose,  // int
  kLineTableHalf,      // int: the phase tables' reach, max |k| of the retained modes
  kLinePartials,       // global float*
  kLineInvLength,      // float4: 1 / L
};

// Writes `selection`'s line records into `records` (a new buffer, a quarter larger than
// needed, when `capacity` records do not fit) and sets the line count, folding, extra
// count and table reach; the extras themselves are the caller's (their types differ).
// Blocking: the caller's vectors change with the next selection. Throws cl::Error.
void upload_line_selection(QueryLaunch& launch, const LineSelection& selection, int table_half, cl::Buffer& records,
                           std::size_t& capacity);

}  // namespace snapfit
