// Per-pose energy, force and torque from the truncated spectra (seed 000 eq. 10-12;
// engine/pose_query.h has the formulas and frames). One work-group reduces a slice of
// the retained modes of one pose; the host adds the groups' partial sums.
//
// Options: -D WG_SIZE=n (power of two)  -D MAX_HALF=h (largest |k| on any axis)
//          -D FORCE  -D TORQUE  -D TRANSLATION_ONLY
//          -D TRICUBIC (Catmull-Rom; default trilinear)  -D HALF_CUBE (cube stored as half)
// Per mode k: w = w_k (part 1's frequency node), weight W_k = S1(w_k) dw, and
//   6-DOF: w' = -R^T w, term = W_k S2(w') e^{i phi}, phi = 2 pi w.tau, tau = t + R c2 - c1
//          (e^{i phi} from per-axis tables built here in local memory: no sincos per mode)
//          torque (part 2 frame): Re[2 pi i W_k e^{i phi} (w' x SQ(w'))]
//   translation only: W_k already holds S1(w_k) S2(-w_k) dw, term = W_k e^{i phi}.
// Partial sums per group (8 floats): Re f, Im f, F (3), T in part 2's frame (3).
//
// The pose (float16): s0-s8 R row-major, s9-sb tau_a / L_a rounded to float ("hi"),
// sc-se the rest tau_a / L_a - hi ("lo"). A single query passes it as the argument
// `pose_arg` (no buffer write); a batch reads poses[pose] (pose_count > 1).
//
// Each mode is one float4: (Re W_k, Im W_k, (kx, ky) as two shorts, kz as an int),
// so the mode loop streams 16 bytes per mode from one array.

// The spectrum of part 2 near the low-pass ball, as a compact cube (no wrapping):
// signed FFT index i sits at cube index i + offset. With torque each node holds
// S2, SQ_x, SQ_y, SQ_z interleaved (one 32-byte load per tap, 16 with HALF_CUBE;
// half values are scaled by 1 / max |component| and scaled back here).
#ifdef TORQUE
typedef float8 Sample;
#ifdef HALF_CUBE
#define LOAD_SAMPLE(i) vload_half8((i), cube)
#endif
#else
typedef float2 Sample;
#ifdef HALF_CUBE
#define LOAD_SAMPLE(i) vload_half2((i), cube)
#endif
#endif
#ifdef HALF_CUBE
#define CUBE_T half
#else
#define CUBE_T Sample
#define LOAD_SAMPLE(i) cube[(i)]
#endif

// e^{2 pi i k x} for x = hi + lo (tau_a / L_a as a float pair), reduced to a fraction
// of a turn first: k * hi is split exactly with fma, so |phase error| stays ~1e-7 rad
// for every |k| (as the host's double-precision tables were).
inline float2 axis_phase(const int k, const float hi, const float lo) {
  const float kf = (float)k;
  const float p = kf * hi;
  const float e = fma(kf, hi, -p);                // k hi = p + e exactly
  const float turns = (p - rint(p)) + (e + kf * lo);  // k x mod 1, in [-0.5, 0.5] + tiny
  return (float2)(cospi(2.0f * turns), sinpi(2.0f * turns));
}

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1)))
void pose_query(__global const float4* modes, __global const CUBE_T* cube,
                const int4 cube_dims, const int4 offset, const float4 length, const float4 cube_scale,
                const float16 pose_arg, __global const float16* poses, const int pose_count,
                const int mode_count, const int groups_per_pose, const int table_half,
                __global float* partials) {
  const int group = get_group_id(0);
  const int pose = group / groups_per_pose;
  const int slice = group % groups_per_pose;
  const int lid = get_local_id(0);
  const float16 P = pose_count > 1 ? poses[pose] : pose_arg;

  // exp(2 pi i w.tau) is separable per axis (DESIGN.md): tables of
  // exp(2 pi i k tau_a / L_a) for |k| <= table_half, one per axis, built by the group.
  __local float2 tables[3 * (2 * MAX_HALF + 1)];
  __local float2* tx = tables + MAX_HALF;
  __local float2* ty = tx + (2 * MAX_HALF + 1);
  __local float2* tz = ty + (2 * MAX_HALF + 1);
  for (int k = lid - table_half; k <= table_half; k += WG_SIZE) {
    tx[k] = axis_phase(k, P.s9, P.sc);
    ty[k] = axis_phase(k, P.sa, P.sd);
    tz[k] = axis_phase(k, P.sb, P.se);
  }
  barrier(CLK_LOCAL_MEM_FENCE);

  float2 f = (float2)(0.0f);
  float3 force = (float3)(0.0f), torque = (float3)(0.0f);
  for (int m = slice * WG_SIZE + lid; m < mode_count; m += groups_per_pose * WG_SIZE) {
    const float4 mode = modes[m];
    const short2 kxy = as_short2(mode.z);
    const int3 k = (int3)(kxy.x, kxy.y, as_int(mode.w));
    const float3 w = convert_float3(k) / length.xyz;  // w_k = k / L
    float2 term = cmul(mode.xy, cmul(tx[k.x], cmul(ty[k.y], tz[k.z])));
#ifndef TRANSLATION_ONLY
    // w' = -R^T w (R^T's rows are R's columns).
    const float3 wp = -(float3)(P.s0 * w.x + P.s3 * w.y + P.s6 * w.z, P.s1 * w.x + P.s4 * w.y + P.s7 * w.z,
                                P.s2 * w.x + P.s5 * w.y + P.s8 * w.z);
    const float3 u = wp * length.xyz;  // fractional FFT index
    float wx[TAPS], wy[TAPS], wz[TAPS];
    const int ix = axis_weights(u.x, wx), iy = axis_weights(u.y, wy), iz = axis_weights(u.z, wz);
    Sample acc = (Sample)(0.0f);
    for (int c3 = 0; c3 < TAPS; ++c3) {
      const int z = iz + c3 + offset.z;
      for (int b = 0; b < TAPS; ++b) {
        const int row = cube_dims.x * (cube_dims.y * z + iy + b + offset.y) + ix + offset.x;
        const float wyz = wy[b] * wz[c3];
        for (int a = 0; a < TAPS; ++a) acc += (wx[a] * wyz) * LOAD_SAMPLE(row + a);
      }
    }
#ifdef TORQUE
    const float2 v = acc.s01 * cube_scale.x;
    const float2 q0 = acc.s23 * cube_scale.y, q1 = acc.s45 * cube_scale.y, q2 = acc.s67 * cube_scale.y;
    // 2 pi i term_q (w' x SQ): Re of i z is -Im z.
    const float2 e = term;  // W_k e^{i phi}
    const float2 t0 = cmul(e, q0), t1 = cmul(e, q1), t2 = cmul(e, q2);
    const float3 im = (float3)(wp.y * t2.y - wp.z * t1.y, wp.z * t0.y - wp.x * t2.y, wp.x * t1.y - wp.y * t0.y);
    torque += -TWO_PI * im;
#else
    const float2 v = acc * cube_scale.x;
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
