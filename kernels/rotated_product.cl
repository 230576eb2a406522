// The product spectrum of the pair for part 2 turned by R0, exact in rotation
// (engine/query/rotated_product.h; docs/design.md "Exact rotation"): for each listed mode k,
// with w = k / L and part 2's rotated frequency u = -R0^T w,
//   W0_k = S1(w) dw S2(u)                       (the energy's term)
//   D_k  = S1(w) dw (w x R0 grad S2(u))          (its rotation derivative, d/dtheta)
// where S2 and its gradient are evaluated exactly (to the kernel's tolerance) from part
// 2's deconvolved spectrum by the exponential-of-semicircle kernel (engine/spectra/es_kernel.h):
//   S2(u) = sum_n phi(L u - n) S2'_n,  dS2/du_a = L_a sum_n phi'(L_a u_a - n_a) ... S2'_n.
// Output per mode: float8 (W0, D_x, D_y, D_z) at its node of the product box; with
// conjugate pairs (both parts' samples imaginary: W0(-w) = conj W0(w), D(-w) = conj D(w))
// also the conjugate at the partner's node, so one evaluation serves the pair.
//
// Options: -D ES_WIDTH=w (taps per axis)  -D ES_BETA=b (the kernel's shape)

#define TWO_PI 6.28318530717958647f

inline float2 cmul(const float2 a, const float2 b) { return (float2)(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

inline int wrap(const int i, const int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

// Kernel values and derivatives at the ES_WIDTH taps around fractional node x: taps
// first + j, j = 0 .. ES_WIDTH - 1 (phi(x - tap), d/dx phi(x - tap)).
inline int es_weights(const float x, float* value, float* slope) {
  const int first = (int)ceil(x - 0.5f * ES_WIDTH);
  for (int j = 0; j < ES_WIDTH; ++j) {
    const float t = 2.0f * (x - (float)(first + j)) / ES_WIDTH;
    const float q = 1.0f - t * t;
    if (q > 0.0f) {
      const float root = sqrt(q);
      value[j] = exp(ES_BETA * (root - 1.0f));
      slope[j] = value[j] * ES_BETA * (-t / root) * (2.0f / ES_WIDTH);
    } else {
      value[j] = 0.0f;
      slope[j] = 0.0f;
    }
  }
  return first;
}

// modes[i] = (product-box node, kx, ky, kz); s1w[i] = S1(w_k) dw (centred, docs/design.md);
// partners[i]: the box node of -k, or -1 (none, or its own). rotation: R0 row-major in s0-s8.
__kernel void rotated_product(__global const int4* modes, __global const float2* s1w, __global const int* partners,
                              const int count, __global const float2* s2d, const int4 dims, const float16 rotation,
                              const float4 length, const float4 inv_length, __global float8* product) {
  const int i = get_global_id(0);
  if (i >= count) return;
  const int4 m = modes[i];
  const float3 w = (float3)((float)m.y, (float)m.z, (float)m.w) * inv_length.xyz;
  const float16 R = rotation;
  // u = -R0^T w (R0^T's rows are R0's columns), as fractional node indices L u.
  const float3 u = -(float3)(R.s0 * w.x + R.s3 * w.y + R.s6 * w.z, R.s1 * w.x + R.s4 * w.y + R.s7 * w.z,
                             R.s2 * w.x + R.s5 * w.y + R.s8 * w.z);
  const float3 x = u * length.xyz;
  float vx[ES_WIDTH], vy[ES_WIDTH], vz[ES_WIDTH], dx[ES_WIDTH], dy[ES_WIDTH], dz[ES_WIDTH];
  const int fx = es_weights(x.x, vx, dx), fy = es_weights(x.y, vy, dy), fz = es_weights(x.z, vz, dz);
  float2 s = (float2)(0.0f), gx = (float2)(0.0f), gy = (float2)(0.0f), gz = (float2)(0.0f);
  for (int c = 0; c < ES_WIDTH; ++c) {
    const int z = wrap(fz + c, dims.z);
    float2 ps = (float2)(0.0f), pgx = (float2)(0.0f), pgy = (float2)(0.0f);
    for (int b = 0; b < ES_WIDTH; ++b) {
      const int row = dims.x * (dims.y * z + wrap(fy + b, dims.y));
      float2 ls = (float2)(0.0f), lgx = (float2)(0.0f);
      for (int a = 0; a < ES_WIDTH; ++a) {
        const float2 v = s2d[row + wrap(fx + a, dims.x)];
        ls += vx[a] * v;
        lgx += dx[a] * v;
      }
      ps += vy[b] * ls;
      pgx += vy[b] * lgx;
      pgy += dy[b] * ls;
    }
    s += vz[c] * ps;
    gx += vz[c] * pgx;
    gy += vz[c] * pgy;
    gz += dz[c] * ps;
  }
  // d/du_a = L_a d/dx_a; the gradient to part 1's frame: R0 g.
  gx *= length.x;
  gy *= length.y;
  gz *= length.z;
  const float2 g0 = R.s0 * gx + R.s1 * gy + R.s2 * gz;
  const float2 g1 = R.s3 * gx + R.s4 * gy + R.s5 * gz;
  const float2 g2 = R.s6 * gx + R.s7 * gy + R.s8 * gz;
  const float2 a = s1w[i];
  // w x (R0 g), component by component (g complex).
  const float2 c0 = w.y * g2 - w.z * g1, c1 = w.z * g0 - w.x * g2, c2 = w.x * g1 - w.y * g0;
  const float2 w0 = cmul(a, s), d0 = cmul(a, c0), d1 = cmul(a, c1), d2 = cmul(a, c2);
  product[m.x] = (float8)(w0, d0, d1, d2);
  const int partner = partners[i];
  if (partner >= 0) product[partner] = (float8)(w0.x, -w0.y, d0.x, -d0.y, d1.x, -d1.y, d2.x, -d2.y);
}
