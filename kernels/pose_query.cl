// Per-pose energy, force and torque from the truncated spectra (seed 000 eq. 10-12;
// engine/pose_query.h has the formulas and frames). One work-group reduces a slice of
// the retained modes of one pose; the host adds the groups' partial sums.
//
// Options: -D WG_SIZE=n (power of two)  -D FORCE  -D TORQUE  -D TRANSLATION_ONLY
//          -D TRICUBIC (Catmull-Rom; default trilinear)
// Per mode k: w = w_k (part 1's frequency node), weight W_k = S1(w_k) dw, and
//   6-DOF: w' = -R^T w, term = W_k S2(w') e^{i phi}, phi = 2 pi w.tau, tau = t + R c2 - c1
//          (e^{i phi} from per-axis tables: no sincos per mode)
//          torque (part 2 frame): Re[2 pi i W_k e^{i phi} (w' x SQ(w'))]
//   translation only: W_k already holds S1(w_k) S2(-w_k) dw, term = W_k e^{i phi}.
// Partial sums per group (8 floats): Re f, Im f, F (3), T in part 2's frame (3).

// The spectrum of part 2 near the low-pass ball, as a compact cube (no wrapping):
// signed FFT index i sits at cube index i + offset. With torque each node holds
// S2, SQ_x, SQ_y, SQ_z interleaved (one 32-byte load per tap).
#ifdef TORQUE
typedef float8 Sample;
#else
typedef float2 Sample;
#endif

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1)))
void pose_query(__global const float2* weights, __global const Sample* cube,
                const int4 cube_dims, const int4 offset, const float4 length, __global const float* poses,
                const int mode_count, const int groups_per_pose, __global const short4* mode_index,
                __global const float2* phase_tables, const int table_half, __global float* partials) {
  const int group = get_group_id(0);
  const int pose = group / groups_per_pose;
  const int slice = group % groups_per_pose;
  const int lid = get_local_id(0);
  __global const float* P = poses + 12 * pose;  // R row-major (9), tau (3)
  // exp(2 pi i w.tau) is separable per axis (DESIGN.md): the host tabulates
  // exp(2 pi i k tau_a / L_a) for |k| <= table_half, per pose and axis.
  const int table = 2 * table_half + 1;
  __global const float2* tx = phase_tables + 3 * table * pose + table_half;
  __global const float2* ty = tx + table;
  __global const float2* tz = ty + table;

  float2 f = (float2)(0.0f);
  float3 force = (float3)(0.0f), torque = (float3)(0.0f);
  for (int m = slice * WG_SIZE + lid; m < mode_count; m += groups_per_pose * WG_SIZE) {
    const int4 k = convert_int4(mode_index[m]);
    const float3 w = convert_float3(k.xyz) / length.xyz;  // w_k = k / L
    float2 term = cmul(weights[m], cmul(tx[k.x], cmul(ty[k.y], tz[k.z])));
#ifndef TRANSLATION_ONLY
    // w' = -R^T w (R^T's rows are R's columns).
    const float3 wp = -(float3)(P[0] * w.x + P[3] * w.y + P[6] * w.z, P[1] * w.x + P[4] * w.y + P[7] * w.z,
                                P[2] * w.x + P[5] * w.y + P[8] * w.z);
    const float3 u = wp * length.xyz;  // fractional FFT index
    float wx[TAPS], wy[TAPS], wz[TAPS];
    const int ix = axis_weights(u.x, wx), iy = axis_weights(u.y, wy), iz = axis_weights(u.z, wz);
    Sample acc = (Sample)(0.0f);
    for (int c3 = 0; c3 < TAPS; ++c3) {
      const int z = iz + c3 + offset.z;
      for (int b = 0; b < TAPS; ++b) {
        const int row = cube_dims.x * (cube_dims.y * z + iy + b + offset.y) + ix + offset.x;
        const float wyz = wy[b] * wz[c3];
        for (int a = 0; a < TAPS; ++a) acc += (wx[a] * wyz) * cube[row + a];
      }
    }
#ifdef TORQUE
    const float2 v = acc.s01, q0 = acc.s23, q1 = acc.s45, q2 = acc.s67;
#else
    const float2 v = acc;
#endif
#ifdef TORQUE
    // 2 pi i term_q (w' x SQ): Re of i z is -Im z.
    const float2 e = term;  // W_k e^{i phi}
    const float2 t0 = cmul(e, q0), t1 = cmul(e, q1), t2 = cmul(e, q2);
    const float3 im = (float3)(wp.y * t2.y - wp.z * t1.y, wp.z * t0.y - wp.x * t2.y, wp.x * t1.y - wp.y * t0.y);
    torque += -TWO_PI * im;
#endif
    term = cmul(term, v);
#endif
    f += term;
#ifdef FORCE
    force += -TWO_PI * term.y * w;  // Re(2 pi i w term)
#endif
  }

  // Work-group reduction of the 8 sums.
  __local float scratch[8 * WG_SIZE];
  scratch[8 * lid + 0] = f.x;
  scratch[8 * lid + 1] = f.y;
  scratch[8 * lid + 2] = force.x;
  scratch[8 * lid + 3] = force.y;
  scratch[8 * lid + 4] = force.z;
  scratch[8 * lid + 5] = torque.x;
  scratch[8 * lid + 6] = torque.y;
  scratch[8 * lid + 7] = torque.z;
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int stride = WG_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride)
      for (int j = 0; j < 8; ++j) scratch[8 * lid + j] += scratch[8 * (lid + stride) + j];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  if (lid < 8) partials[8 * group + lid] = scratch[lid];
}
