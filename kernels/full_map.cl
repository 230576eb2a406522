// Full translational map for one rotation (seed 000 Fig. 1c, 5; docs/design.md "Full map"):
// the product P_k = S1(w_k) S2(-R^T w_k) exp(2 pi i w_k.(R c2 - c1)) dw on every FFT
// node; one unnormalized inverse FFT of P then gives f(R, t) at every grid translation
// t = h j (j signed, periodic). Nodes with |w|^2 > max_w2 are dropped (low-pass ball).
// A launch makes the products of a batch of rotations: global id 1 is the member, whose
// pose is poses[member] and whose product starts at member * (nodes per product).

// P at FFT node (x, y, z). pose: R row-major in s0..s8, shift = R c2 - c1 in s9..sb.
inline float2 product_at(__global const float2* s1, __global const float2* s2, const int4 dims, const float4 length,
                         const float16 pose, const float dw, const float max_w2, const int x, const int y,
                         const int z) {
  const float3 w =
      (float3)((x <= dims.x / 2 ? x : x - dims.x) / length.x, (y <= dims.y / 2 ? y : y - dims.y) / length.y,
               (z <= dims.z / 2 ? z : z - dims.z) / length.z);
  if (dot(w, w) > max_w2) return (float2)(0.0f);
  const float3 wp =
      -(float3)(pose.s0 * w.x + pose.s3 * w.y + pose.s6 * w.z, pose.s1 * w.x + pose.s4 * w.y + pose.s7 * w.z,
                pose.s2 * w.x + pose.s5 * w.y + pose.s8 * w.z);
  const float2 v = sample_spectrum(s2, dims, wp * length.xyz);
  float c;
  const float s = sincos(TWO_PI * dot(w, (float3)(pose.s9, pose.sa, pose.sb)), &c);
  return dw * cmul(cmul(s1[x + dims.x * (y + dims.y * z)], v), (float2)(c, s));
}

// P on every node, for a complex-to-complex inverse FFT.
__kernel void spectrum_product(__global const float2* s1, __global const float2* s2, const int4 dims,
                               const float4 length, __global const float16* poses, const float dw,
                               const float max_w2, __global float2* product) {
  const int k = get_global_id(0), member = get_global_id(1);
  const int nodes = dims.x * dims.y * dims.z;
  if (k >= nodes) return;
  const int x = k % dims.x, y = (k / dims.x) % dims.y, z = k / (dims.x * dims.y);
  product[(size_t)member * nodes + k] = product_at(s1, s2, dims, length, poses[member], dw, max_w2, x, y, z);
}

// The energy needs Re f only, which is the inverse FFT of P's Hermitian part
// H_k = (P_k + conj P_{-k}) / 2 (index -k taken mod N). H is fixed by the half
// x = 0..dims.x/2 (layout x fastest, dims.x/2 + 1 per row), the input of a
// complex-to-real inverse FFT: half the transform and a real map of half the bytes.
// -D CONJUGATE_PAIRS: both parts' samples real, or both imaginary, so P_{-k} = conj P_k
// (engine/spectra/spectra.h sample_parity) and H = P: one product per node instead of two.
__kernel void spectrum_product_half(__global const float2* s1, __global const float2* s2, const int4 dims,
                                    const float4 length, __global const float16* poses, const float dw,
                                    const float max_w2, __global float2* half_product) {
  const int hx = dims.x / 2 + 1;
  const int k = get_global_id(0), member = get_global_id(1);
  const int nodes = hx * dims.y * dims.z;
  if (k >= nodes) return;
  const float16 pose = poses[member];
  half_product += (size_t)member * nodes;
  const int x = k % hx, y = (k / hx) % dims.y, z = k / (hx * dims.y);
  const float2 p = product_at(s1, s2, dims, length, pose, dw, max_w2, x, y, z);
#ifdef CONJUGATE_PAIRS
  half_product[k] = p;
#else
  const float2 q = product_at(s1, s2, dims, length, pose, dw, max_w2, (dims.x - x) % dims.x, (dims.y - y) % dims.y,
                              (dims.z - z) % dims.z);
  half_product[k] = 0.5f * (float2)(p.x + q.x, p.y - q.y);
#endif
}
