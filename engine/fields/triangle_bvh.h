#pragma once
// A bounding-volume hierarchy over a mesh's triangles, laid out for the descriptor
// kernels (kernels/geometry.cl mirrors BvhNode). Each node also stores the moments
// the far-field (cluster) approximations need, as in fast winding numbers
// (Barill et al. 2018): total area A, area-weighted centroid c, radius r of the
// ball around c that holds the node's triangles, area vector N = sum A_t n_t, the
// first moment M = sum A_t n_t (c_t - c)^T, and the second moment
// I = integral over the node's triangles of |q - c|^2 dA (<= r^2 A), which bounds the
// far-field remainders more tightly than r^2 A (kernels/skeletal_density.cl).
#include <CL/opencl.hpp>
#include <vector>

#include "mesh/mesh.h"

namespace snapfit {

// 128 bytes; depth-first order: a node's left child is the next node.
struct BvhNode {
  cl_float4 bbox_min;     // w: total area A
  cl_float4 bbox_max;     // w: radius r around the centroid
  cl_float4 centroid;     // area-weighted centroid c; w: second moment I
  cl_float4 area_normal;  // N = sum A_t n_t
  cl_float4 moment[3];    // rows of M = sum A_t n_t (c_t - c)^T
  cl_int4 links;          // x: right child (-1 for a leaf), y: first triangle, z: triangle count
};
static_assert(sizeof(BvhNode) == 128, "BvhNode must match kernels/geometry.cl");

struct TriangleBvh {
  std::vector<BvhNode> nodes;
  std::vector<cl_float4> triangles;  // 3 per triangle (vertices, w unused), in leaf order
  int depth = 0;
  double total_area = 0;
};

// Builds with median splits along the longest centroid axis, up to `leaf_size`
// triangles per leaf; the top levels are built in parallel with TBB.
// Degenerate (zero-area) triangles are kept: they contribute nothing.
TriangleBvh build_triangle_bvh(const Mesh& mesh, int leaf_size = 4);

}  // namespace snapfit
