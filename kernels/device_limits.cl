// The device's limits for perf/bench_queries' roofline: memory bandwidth (a copy, and
// reads strided for GPUs, blocked for CPUs, and repeated over a cache-sized block) and
// arithmetic peak (independent fma chains). Built with -D ITERS=N, the chains' length.
__kernel void copy_f4(__global const float4* src, __global float4* dst) {
  const size_t i = get_global_id(0);
  dst[i] = src[i];
}
// Each work-item sums every stride-th float4 (coalesced on GPUs).
__kernel void read_strided(__global const float4* src, const uint n, __global float* out) {
  const uint g = get_global_id(0), stride = get_global_size(0);
  float4 s = (float4)(0.0f);
  for (uint i = g; i < n; i += stride) s += src[i];
  out[g] = s.x + s.y + s.z + s.w;
}
// Each work-item sums one contiguous block (streams well on CPUs).
__kernel void read_blocked(__global const float4* src, const uint chunk, __global float* out) {
  const uint g = get_global_id(0);
  __global const float4* p = src + (size_t)g * chunk;
  float4 s0 = (float4)(0.0f), s1 = (float4)(0.0f);
  for (uint i = 0; i < chunk; i += 2) { s0 += p[i]; s1 += p[i + 1]; }
  const float4 s = s0 + s1;
  out[g] = s.x + s.y + s.z + s.w;
}
// Same, each block read `reps` times: a buffer that fits in the last-level cache.
__kernel void read_blocked_repeat(__global const float4* src, const uint chunk, const uint reps, __global float* out) {
  const uint g = get_global_id(0);
  __global const float4* p = src + (size_t)g * chunk;
  float4 s0 = (float4)(0.0f), s1 = (float4)(0.0f);
  for (uint r = 0; r < reps; ++r)
    for (uint i = 0; i < chunk; i += 2) { s0 += p[i]; s1 += p[i + 1]; }
  const float4 s = s0 + s1;
  out[g] = s.x + s.y + s.z + s.w;
}
// 8 independent fma chains per work-item, ITERS steps each.
#define CHAINS(T)                                                                       \
  const float g = (float)get_global_id(0) * 1e-7f;                                      \
  T a0 = (T)(g), a1 = a0 + (T)(0.01f), a2 = a0 + (T)(0.02f), a3 = a0 + (T)(0.03f),      \
    a4 = a0 + (T)(0.04f), a5 = a0 + (T)(0.05f), a6 = a0 + (T)(0.06f), a7 = a0 + (T)(0.07f); \
  const T vb = (T)(b), vc = (T)(c);                                                     \
  for (int i = 0; i < ITERS; ++i) {                                                     \
    a0 = fma(a0, vb, vc); a1 = fma(a1, vb, vc); a2 = fma(a2, vb, vc); a3 = fma(a3, vb, vc); \
    a4 = fma(a4, vb, vc); a5 = fma(a5, vb, vc); a6 = fma(a6, vb, vc); a7 = fma(a7, vb, vc); \
  }                                                                                     \
  const T s = ((a0 + a1) + (a2 + a3)) + ((a4 + a5) + (a6 + a7));
__kernel void fma_f4(const float b, const float c, __global float* out) {
  CHAINS(float4)
  out[get_global_id(0)] = s.x + s.y + s.z + s.w;
}
__kernel void fma_f8(const float b, const float c, __global float* out) {
  CHAINS(float8)
  out[get_global_id(0)] = s.s0 + s.s1 + s.s2 + s.s3 + s.s4 + s.s5 + s.s6 + s.s7;
}
__kernel void fma_f16(const float b, const float c, __global float* out) {
  CHAINS(float16)
  out[get_global_id(0)] = s.s0 + s.s1 + s.s2 + s.s3 + s.s4 + s.s5 + s.s6 + s.s7 + s.s8 + s.s9 + s.sa + s.sb + s.sc + s.sd +
                          s.se + s.sf;
}
