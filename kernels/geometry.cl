// Shared geometry for the descriptor kernels: the BVH node layout (mirrors
// engine/fields/triangle_bvh.h), grid points, point-triangle distance, triangle solid angle.
// Prepended to unsigned_distance.cl, winding_number.cl and skeletal_density.cl.

typedef struct {
  float4 bbox_min;     // w: total area A
  float4 bbox_max;     // w: radius r around the centroid
  float4 centroid;     // area-weighted centroid c; w: I = integral of |q - c|^2 dA
  float4 area_normal;  // N = sum A_t n_t
  float4 moment[3];    // rows of M = sum A_t n_t (c_t - c)^T
  int4 links;          // x: right child (-1: leaf), y: first triangle, z: triangle count
} BvhNode;

#ifndef STACK_SIZE
#define STACK_SIZE 64
#endif

// Grid point number `id`: origin + spacing * (i, j, k), i fastest (core/grid.h).
// With -D EXPLICIT_POINTS the descriptor kernels read each point's coordinates instead,
// from three arrays (x, y, z) holding the chunk's items in order, like their inputs.
inline float3 grid_point(const long id, const float3 origin, const float spacing, const int nx, const int ny) {
  const long i = id % nx;
  const long j = (id / nx) % ny;
  const long k = id / ((long)nx * ny);
  return origin + spacing * (float3)((float)i, (float)j, (float)k);
}

// Squared distance from p to the box [lo, hi] (0 inside).
inline float box_distance2(const float3 p, const float3 lo, const float3 hi) {
  const float3 d = fmax(fmax(lo - p, p - hi), (float3)(0.0f));
  return dot(d, d);
}

// Squared distance from p to triangle (a, b, c): closest-point regions as in
// Ericson, Real-Time Collision Detection, sec. 5.1.5.
inline float point_triangle_distance2(const float3 p, const float3 a, const float3 b, const float3 c) {
  const float3 ab = b - a, ac = c - a, ap = p - a;
  const float d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0.0f && d2 <= 0.0f) return dot(ap, ap);
  const float3 bp = p - b;
  const float d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0.0f && d4 <= d3) return dot(bp, bp);
  const float vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0f && d1 >= 0.0f && d3 <= 0.0f) {
    const float3 q = a + (d1 / (d1 - d3)) * ab;
    return dot(p - q, p - q);
  }
  const float3 cp = p - c;
  const float d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0.0f && d5 <= d6) return dot(cp, cp);
  const float vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0f && d2 >= 0.0f && d6 <= 0.0f) {
    const float3 q = a + (d2 / (d2 - d6)) * ac;
    return dot(p - q, p - q);
  }
  const float va = d3 * d6 - d5 * d4;
  if (va <= 0.0f && (d4 - d3) >= 0.0f && (d5 - d6) >= 0.0f) {
    const float3 q = b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
    return dot(p - q, p - q);
  }
  const float denom = 1.0f / (va + vb + vc);
  const float3 q = a + ab * (vb * denom) + ac * (vc * denom);
  return dot(p - q, p - q);
}

// Signed solid angle of triangle (a, b, c) seen from p (Van Oosterom & Strackee 1983):
// tan(omega/2) = det[a b c] / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|), with a, b, c
// relative to p. Positive when p is behind the face (counter-clockwise seen from the
// outside, outward normal), so a closed mesh gives 4 pi inside and 0 outside.
inline float triangle_solid_angle(const float3 p, const float3 va, const float3 vb, const float3 vc) {
  const float3 a = va - p, b = vb - p, c = vc - p;
  const float la = length(a), lb = length(b), lc = length(c);
  const float det = dot(a, cross(b, c));
  const float div = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
  // p in the triangle's plane (to round-off): the triangle is seen edge-on, solid angle 0.
  // On the triangle itself the one-sided limits are +-2 pi; 0 is their mean, so a point on
  // a face of a closed mesh gets w = 1/2 instead of a round-off-dependent 0 or 1 (or -1/2).
  if (fabs(det) <= 1e-6f * la * lb * lc) return 0.0f;
  return 2.0f * atan2(det, div);
}

// sum_ij J_ij M_ij with J = (I - 3 u^ u^T) / |u|^3, the Jacobian of F(q) = (q - p)/|q - p|^3
// at q = c (u = c - p): the first-order term of a cluster's solid angle (Barill et al. 2018).
inline float first_order_term(const float3 u_hat, const float inv_d3, __global const BvhNode* node) {
  const float3 m0 = node->moment[0].xyz, m1 = node->moment[1].xyz, m2 = node->moment[2].xyz;
  const float trace = m0.x + m1.y + m2.z;
  const float3 mu = (float3)(dot(m0, u_hat), dot(m1, u_hat), dot(m2, u_hat));
  return (trace - 3.0f * dot(u_hat, mu)) * inv_d3;
}
