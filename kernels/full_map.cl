// Full translational map for one rotation (seed 000 Fig. 1c, 5; docs/design.md "Full map"):
// the product P_k = S1(w_k) S2(-R^T w_k) exp(2 pi i w_k.(R c2 - c1)) dw on every FFT
// node; one unnormalized inverse FFT of P then gives f(R, t) at every grid translation
// t = h j (j signed, periodic). Nodes with |w|^2 > max_w2 are dropped (low-pass ball).

__kernel void spectrum_product(__global const float2* s1, __global const float2* s2, const int4 dims,
                               const float4 length, const float16 pose, const float dw, const float max_w2,
                               __global float2* product) {
  const int k = get_global_id(0);
  if (k >= dims.x * dims.y * dims.z) return;
  const int x = k % dims.x, y = (k / dims.x) % dims.y, z = k / (dims.x * dims.y);
  const float3 w =
      (float3)((x <= dims.x / 2 ? x : x - dims.x) / length.x, (y <= dims.y / 2 ? y : y - dims.y) / length.y,
               (z <= dims.z / 2 ? z : z - dims.z) / length.z);
  if (dot(w, w) > max_w2) {
    product[k] = (float2)(0.0f);
    return;
  }
  // pose: R row-major in s0..s8, shift = R c2 - c1 in s9..sb.
  const float3 wp =
      -(float3)(pose.s0 * w.x + pose.s3 * w.y + pose.s6 * w.z, pose.s1 * w.x + pose.s4 * w.y + pose.s7 * w.z,
                pose.s2 * w.x + pose.s5 * w.y + pose.s8 * w.z);
  const float2 v = sample_spectrum(s2, dims, wp * length.xyz);
  float c;
  const float s = sincos(TWO_PI * dot(w, (float3)(pose.s9, pose.sa, pose.sb)), &c);
  product[k] = dw * cmul(cmul(s1[k], v), (float2)(c, s));
}
