// Per-pose energy, force and torque from the truncated spectra (seed 000 eq. 10-12;
// include/snapfit/query.h has the formulas and frames). One work-group reduces a slice of
// the retained modes of one pose; the host adds the groups' partial sums.
//
// Options: -D WG_SIZE=n (power of two)  -D MAX_HALF=h (largest |k| on any axis)
//          -D FORCE  -D TORQUE  -D TRANSLATION_ONLY  -D ROTATED_LINES (with TRANSLATION_ONLY)
//          -D TRICUBIC (Catmull-Rom; default trilinear)  -D HALF_CUBE (cube stored as half)
// Per mode k: w = w_k (part 1's frequency node), weight W_k = S1(w_k) dw, and
//   6-DOF: w' = -R^T w, term = W_k S2(w') e^{i phi}, phi = 2 pi w.tau, tau = t + R c2 - c1
//          (e^{i phi} from per-axis tables built here in local memory: no sincos per mode)
//          torque: the derivative of the same interpolated energy under R -> exp(theta e) R
//          (include/snapfit/query.h), Re[W_k e^{i phi} (grad S2(w') x w')] in part 2's frame
//          (the host adds R c2 x F for the rotating box centre), so E, F, T are consistent
//   translation only: W_k already holds S1(w_k) S2(-w_k) dw, term = W_k e^{i phi}.
// Partial sums per group (24 floats, SUMS_PER_GROUP): the 8 outputs Re f, Im f, F (3),
// T in part 2's frame (3) over every retained mode, then the same 8 over the two octave
// bands just below the cut, modes (m'/4, m'/2] and (m'/2, m'] (from which the host
// estimates the truncation error, engine/query/error_estimate.h).
//
// The pose (float16): s0-s8 R row-major, s9-sb tau_a / L_a rounded to float ("hi"),
// sc-se the rest tau_a / L_a - hi ("lo"). A single query passes it as the argument
// `pose_arg` (no buffer write); a batch reads poses[pose] (pose_count > 1).
//
// Each record is one float4: (Re W_k, Im W_k, (kx, ky) as two shorts, (kz, folded) as
// two shorts), so the loop streams 16 bytes per record from one array, in the mode order
// (engine/spectra/mode_order.h: any m' is a prefix). A folded record stands for the conjugate
// pair w, -w of a real correlation: its weight is 2 W_k and it adds to the real parts
// only (Re f, F, T; the pair's Im f is 0). An m' that cuts a pair passes the pair's first
// mode alone as `extra_mode` (weight 0 otherwise), added once per pose.

// The spectrum of part 2 near the low-pass ball, as a compact cube (no wrapping):
// signed FFT index i sits at cube index i + offset (one 8-byte load per tap, 4 with
// HALF_CUBE; half values are scaled by 1 / max |component| and scaled back here).
#ifdef HALF_CUBE
#define CUBE_T half
#define LOAD_SAMPLE(i) vload_half2((i), cube)
#else
#define CUBE_T float2
#define LOAD_SAMPLE(i) cube[(i)]
#endif

// The interpolated sample and, with TORQUE, its gradient in fractional cube index.
typedef struct {
  float2 v;
#ifdef TORQUE
  float2 gx, gy, gz;
#endif
} Sample;

// e^{2 pi i k x} for x = hi + lo (tau_a / L_a as a float pair), reduced to a fraction
// of a turn first: k * hi is split exactly with fma, so |phase error| stays ~1e-7 rad
// for every |k| (as the host's double-precision tables were).
inline float2 axis_phase(const int k, const float hi, const float lo) {
  const float kf = (float)k;
  const float p = kf * hi;
  const float e = fma(kf, hi, -p);                    // k hi = p + e exactly
  const float turns = (p - rint(p)) + (e + kf * lo);  // k x mod 1, in [-0.5, 0.5] + tiny
  return (float2)(cospi(2.0f * turns), sinpi(2.0f * turns));
}

// The spectrum sample at fractional cube index u (rows summed first, then planes:
// short dependency chains, so the loads of neighbouring taps overlap).
#ifndef TRANSLATION_ONLY
__attribute__((always_inline)) inline Sample sample_cube(__global const CUBE_T* cube, const int4 cube_dims,
                                                         const int4 offset, const float3 u) {
  float wx[TAPS], wy[TAPS], wz[TAPS], dwx[TAPS], dwy[TAPS], dwz[TAPS];
  const int ix = axis_weights(u.x, wx, dwx) + offset.x, iy = axis_weights(u.y, wy, dwy) + offset.y,
            iz = axis_weights(u.z, wz, dwz) + offset.z;
  Sample acc;
  acc.v = (float2)(0.0f);
#ifdef TORQUE
  acc.gx = acc.gy = acc.gz = (float2)(0.0f);
#endif
#pragma unroll
  for (int c = 0; c < TAPS; ++c) {
    float2 plane = (float2)(0.0f);
#ifdef TORQUE
    float2 plane_x = (float2)(0.0f), plane_y = (float2)(0.0f);
#endif
#pragma unroll
    for (int b = 0; b < TAPS; ++b) {
      const int row = cube_dims.x * (cube_dims.y * (iz + c) + iy + b) + ix;
      float2 line = (float2)(0.0f);
#ifdef TORQUE
      float2 line_x = (float2)(0.0f);
#endif
#pragma unroll
      for (int a = 0; a < TAPS; ++a) {
        const float2 sample = LOAD_SAMPLE(row + a);
        line += wx[a] * sample;
#ifdef TORQUE
        line_x += dwx[a] * sample;
#endif
      }
      plane += wy[b] * line;
#ifdef TORQUE
      plane_x += wy[b] * line_x;
      plane_y += dwy[b] * line;
#endif
    }
    acc.v += wz[c] * plane;
#ifdef TORQUE
    acc.gx += wz[c] * plane_x;
    acc.gy += wz[c] * plane_y;
    acc.gz += dwz[c] * plane;
#endif
  }
  return acc;
}
#endif

// The 8 outputs of one sum (Re f, Im f, F, T), for a total and for each band.
typedef struct {
  float2 f;
  float3 force, torque;
} Sums;

#define SUMS_PER_GROUP 24

inline Sums zero_sums() {
  Sums s;
  s.f = (float2)(0.0f);
  s.force = s.torque = (float3)(0.0f);
  return s;
}

inline void add_sums(Sums* a, const Sums b) {
  a->f += b.f;
  a->force += b.force;
  a->torque += b.torque;
}

inline void put_sums(float* v, const Sums s) {
  v[0] = s.f.x;
  v[1] = s.f.y;
  v[2] = s.force.x;
  v[3] = s.force.y;
  v[4] = s.force.z;
  v[5] = s.torque.x;
  v[6] = s.torque.y;
  v[7] = s.torque.z;
}

// The work-group's sums of (total, band (m'/4, m'/2], band (m'/2, m']) into
// out[0..23]: a tree reduction in `scratch` (24 * WG_SIZE floats of local memory); the
// first work-items write them out, each value once, however few items the group has.
inline void reduce_partials(__local float* scratch, const int lid, const Sums total, const Sums band_a,
                            const Sums band_b, __global float* out) {
  float v[SUMS_PER_GROUP];
  put_sums(v, total);
  put_sums(v + 8, band_a);
  put_sums(v + 16, band_b);
  for (int j = 0; j < SUMS_PER_GROUP; ++j) scratch[SUMS_PER_GROUP * lid + j] = v[j];
  barrier(CLK_LOCAL_MEM_FENCE);
  for (int stride = WG_SIZE / 2; stride > 0; stride >>= 1) {
    if (lid < stride)
      for (int j = 0; j < SUMS_PER_GROUP; ++j)
        scratch[SUMS_PER_GROUP * lid + j] += scratch[SUMS_PER_GROUP * (lid + stride) + j];
    barrier(CLK_LOCAL_MEM_FENCE);
  }
  for (int j = lid; j < SUMS_PER_GROUP; j += WG_SIZE) out[j] = scratch[j];
}

// One mode's term (seed 000 eq. 10-12) added to the sums f, force, torque.
__attribute__((always_inline)) inline void add_mode(const float4 mode, const float16 P, __local const float2* tx,
                                                    __local const float2* ty, __local const float2* tz,
                                                    __global const CUBE_T* cube, const int4 cube_dims,
                                                    const int4 offset, const float4 length, const float4 inv_length,
                                                    const float4 cube_scale, Sums* sums) {
  const short2 kxy = as_short2(mode.z), kzf = as_short2(mode.w);
  const int3 k = (int3)(kxy.x, kxy.y, kzf.x);
  const float3 w = convert_float3(k) * inv_length.xyz;  // w_k = k / L
  float2 term = cmul(mode.xy, cmul(tx[k.x], cmul(ty[k.y], tz[k.z])));
#ifndef TRANSLATION_ONLY
  // w' = -R^T w (R^T's rows are R's columns), as a fractional FFT index u = w' L.
  const float3 wp = -(float3)(P.s0 * w.x + P.s3 * w.y + P.s6 * w.z, P.s1 * w.x + P.s4 * w.y + P.s7 * w.z,
                              P.s2 * w.x + P.s5 * w.y + P.s8 * w.z);
  const Sample s = sample_cube(cube, cube_dims, offset, wp * length.xyz);
#ifdef TORQUE
  // Re[e (grad S2 x w')], grad in physical units: d/dw'_a = L_a d/du_a.
  const float2 gx = s.gx * (cube_scale.x * length.x), gy = s.gy * (cube_scale.x * length.y),
               gz = s.gz * (cube_scale.x * length.z);
  const float2 e = term;  // W_k e^{i phi}
  const float ex = cmul(e, gx).x, ey = cmul(e, gy).x, ez = cmul(e, gz).x;
  sums->torque += (float3)(ey * wp.z - ez * wp.y, ez * wp.x - ex * wp.z, ex * wp.y - ey * wp.x);
#endif
  term = cmul(term, s.v * cube_scale.x);
#endif
  sums->f += kzf.y ? (float2)(term.x, 0.0f) : term;
#ifdef FORCE
  sums->force += -TWO_PI * term.y * w;  // Re(2 pi i w term)
#endif
}

// Adds records m, m + stride, ... below `end` to `sums` (two per iteration into separate
// sums: independent work for the core to overlap) and leaves m at the first index >= end.
#define ADD_MODE_RECORD(record, sums) \
  add_mode(record, P, tx, ty, tz, cube, cube_dims, offset, length, inv_length, cube_scale, sums)
#define ADD_MODE(index, sums) ADD_MODE_RECORD(modes[index], sums)
#define SUM_RECORDS(m, end, stride, sums)       \
  {                                             \
    Sums other = zero_sums();                   \
    for (; m + stride < end; m += 2 * stride) { \
      ADD_MODE(m, &sums);                       \
      ADD_MODE(m + stride, &other);             \
    }                                           \
    if (m < end) {                              \
      ADD_MODE(m, &sums);                       \
      m += stride;                              \
    }                                           \
    add_sums(&sums, other);                     \
  }

__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void pose_query(
    __global const float4* modes, __global const CUBE_T* cube, const int4 cube_dims, const int4 offset,
    const float4 length, const float4 cube_scale, const float16 pose_arg, __global const float16* poses,
    const int pose_count, const int mode_count, const int groups_per_pose, const int table_half,
    __global float* partials, const float4 inv_length, const float4 extra_mode, const int2 band_starts) {
  const int group = get_group_id(0);
  const int pose = group / groups_per_pose;
  const int slice = group % groups_per_pose;
  const int lid = get_local_id(0);
  const float16 P = pose_count > 1 ? poses[pose] : pose_arg;

  // exp(2 pi i w.tau) is separable per axis (docs/design.md): tables of
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

  // Records [0, band_starts.x) hold the modes up to m'/4, [band_starts.x, band_starts.y)
  // those up to m'/2, the rest up to m' (with the cut pair's extra mode).
  Sums core = zero_sums(), band_a = zero_sums(), band_b = zero_sums();
  const int stride = groups_per_pose * WG_SIZE;
  int m = slice * WG_SIZE + lid;
  SUM_RECORDS(m, band_starts.x, stride, core);
  SUM_RECORDS(m, band_starts.y, stride, band_a);
  SUM_RECORDS(m, mode_count, stride, band_b);
  if (slice == 0 && lid == 0) ADD_MODE_RECORD(extra_mode, &band_b);
  add_sums(&core, band_a);
  add_sums(&core, band_b);

  __local float scratch[SUMS_PER_GROUP * WG_SIZE];
  reduce_partials(scratch, lid, core, band_a, band_b, partials + SUMS_PER_GROUP * group);
}

#ifdef TRANSLATION_ONLY
// (s, s_x) of a line over kx in [lo, hi] (empty when hi < lo): the 8-wide complex dot
// products of W with the x table, masked past hi.
inline float4 line_segment(__global const float* row, __local const float2* tx, const int lo, const int hi) {
  const float8 lane = (float8)(0.0f, 1.0f, 2.0f, 3.0f, 4.0f, 5.0f, 6.0f, 7.0f);
  const float last = (float)hi;
  float8 sr = (float8)(0.0f), si = (float8)(0.0f), sxr = (float8)(0.0f), sxi = (float8)(0.0f);
  for (int x = lo; x <= hi; x += 8) {
    const float16 w = vload16(0, row + 2 * x);
    const float16 t = vload16(0, (__local const float*)(tx + x));
    const float8 kx = (float8)((float)x) + lane;
    const int8 keep = kx <= (float8)(last);
    const float8 pr = select((float8)(0.0f), w.even * t.even - w.odd * t.odd, keep);
    const float8 pim = select((float8)(0.0f), w.even * t.odd + w.odd * t.even, keep);
    sr += pr;
    si += pim;
    sxr += kx * pr;
    sxi += kx * pim;
  }
  const float4 r4 = sr.lo + sr.hi, i4 = si.lo + si.hi, xr4 = sxr.lo + sxr.hi, xi4 = sxi.lo + sxi.hi;
  return (float4)(r4.x + r4.y + r4.z + r4.w, i4.x + i4.y + i4.z + i4.w, xr4.x + xr4.y + xr4.z + xr4.w,
                  xi4.x + xi4.y + xi4.z + xi4.w);
}

// A line's (s, s_x) times p = ty[ky] tz[kz] into f and F.
inline void add_line(Sums* sums, const float4 seg, const float2 p, const short2 kyz, const float real_weight,
                     const int folded, const float4 inv_length) {
  const float2 term = real_weight * cmul(seg.xy, p);
  sums->f += (float2)(term.x, folded ? 0.0f : term.y);
#ifdef FORCE
  sums->force += -TWO_PI * (float3)(real_weight * cmul(seg.zw, p).y, (float)kyz.x * term.y, (float)kyz.y * term.y) *
                 inv_length.xyz;
#endif
}

// Translation only (seed 000 section 3.3; R = I): f(t) = sum_k W_k e^{2 pi i w_k.tau} with
// W_k = S1(w_k) S2(-w_k) dw, stored in a dense box of x-lines (kx fastest; rows padded
// by 8 nodes). engine/query/translation_lines.h picks, for the current m', the lines that
// hold retained modes and on each the interval [xa, xb] of retained kx (|w| grows with
// |kx| along a line, so that is one interval): `lines` holds (index of the line's kx = 0
// node, (ky, kz) as two shorts, xa, xb, then the nested intervals of the modes up to m'/2
// and m'/4, for the band sums). Per line the phase factors, e^{i phi} =
// tx[kx] (ty[ky] tz[kz]) (docs/design.md, separable per axis), so the line is a contiguous,
// 8-wide complex dot product of W with the x table:
//   s = sum_kx W tx[kx],  s_x = sum_kx kx W tx[kx];  f += s p,  p = ty[ky] tz[kz],
//   F = Re(2 pi i w f-terms) = -2 pi (Im(s_x p) / L_x, ky Im(s p) / L_y, kz Im(s p) / L_z).
// With `folded` (a real correlation: the terms at k and -k are complex conjugates) the
// lines are one half of the box, each node stands for its pair: twice its real part
// (Re f, F) and nothing in Im f. `extras` (float4: W, (kx, ky), (kz, code) as shorts)
// are single terms added once per pose: code 1 weighs 1 everywhere (the mode of a pair
// that m' cuts), code 2 weighs -1 in the real outputs and +1 in Im f (a node without a
// partner, which the folded lines counted twice).
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void translation_lines(
    __global const float2* W, __global const int8* lines, __global const float4* extras, const int extra_count,
    const int folded, const float16 pose_arg, __global const float16* poses, const int pose_count, const int line_count,
    const int groups_per_pose, const int table_half, __global float* partials, const float4 inv_length) {
  const int group = get_group_id(0);
  const int pose = group / groups_per_pose;
  const int slice = group % groups_per_pose;
  const int lid = get_local_id(0);
  const float16 P = pose_count > 1 ? poses[pose] : pose_arg;

  // Tables for |k| <= table_half; x up to table_half + 7 (the last 8-wide chunk of a
  // line reaches 7 beyond its interval: masked, but the values must be finite).
#define PAD_HALF (MAX_HALF + 8)
  __local float2 tables[3 * (2 * PAD_HALF + 1)];
  __local float2* tx = tables + PAD_HALF;
  __local float2* ty = tx + (2 * PAD_HALF + 1);
  __local float2* tz = ty + (2 * PAD_HALF + 1);
  const int reach = min(table_half, MAX_HALF);
  for (int k = lid - reach; k <= reach + 7; k += WG_SIZE) {
    tx[k] = axis_phase(k, P.s9, P.sc);
    if (k <= reach) {
      ty[k] = axis_phase(k, P.sa, P.sd);
      tz[k] = axis_phase(k, P.sb, P.se);
    }
  }
  barrier(CLK_LOCAL_MEM_FENCE);

  const float real_weight = folded ? 2.0f : 1.0f;
  Sums core = zero_sums(), band_a = zero_sums(), band_b = zero_sums();
  for (int l = slice * WG_SIZE + lid; l < line_count; l += groups_per_pose * WG_SIZE) {
    const int8 line = lines[l];
    const short2 kyz = as_short2(line.s1);
    __global const float* row = (__global const float*)(W + line.s0);
    const float2 p = cmul(ty[kyz.x], tz[kyz.y]);
    // The interval [xa, xb] as the core [qa, qb] (modes up to m'/4), band a around it
    // (up to m'/2: [ha, qa - 1] and [qb + 1, hb]) and band b outside that.
    add_line(&core, line_segment(row, tx, line.s6, line.s7), p, kyz, real_weight, folded, inv_length);
    add_line(&band_a, line_segment(row, tx, line.s4, line.s6 - 1) + line_segment(row, tx, line.s7 + 1, line.s5), p, kyz,
             real_weight, folded, inv_length);
    add_line(&band_b, line_segment(row, tx, line.s2, line.s4 - 1) + line_segment(row, tx, line.s5 + 1, line.s3), p, kyz,
             real_weight, folded, inv_length);
  }
  if (slice == 0 && lid == 0) {
    for (int e = 0; e < extra_count; ++e) {
      const float4 mode = extras[e];
      const short2 kxy = as_short2(mode.z), kzc = as_short2(mode.w);
      const float2 term = cmul(mode.xy, cmul(tx[kxy.x], cmul(ty[kxy.y], tz[kzc.x])));
      const float real = kzc.y == 1 ? 1.0f : -1.0f;
      Sums* to = kzc.y == 1 ? &band_b : &core;  // code 1: the pair m' cuts
      to->f += (float2)(real * term.x, term.y);
#ifdef FORCE
      to->force += -TWO_PI * real * term.y * convert_float3((int3)(kxy.x, kxy.y, kzc.x)) * inv_length.xyz;
#endif
    }
  }
  add_sums(&core, band_a);
  add_sums(&core, band_b);

  __local float scratch[SUMS_PER_GROUP * WG_SIZE];
  reduce_partials(scratch, lid, core, band_a, band_b, partials + SUMS_PER_GROUP * group);
}
#endif

#ifdef ROTATED_LINES
// A line's sums over kx in [lo, hi] (empty when hi < lo): s = sum W_k t, s_x = sum kx W_k t,
// and d_a = sum D_a,k t, with W_k = W0_k + dtheta . D_k and t = tx[kx].
typedef struct {
  float2 s, sx, d0, d1, d2;
} RotatedSegment;

inline RotatedSegment rotated_segment(__global const float8* row, __local const float2* tx, const float3 dtheta,
                                      const int lo, const int hi) {
  RotatedSegment r;
  r.s = r.sx = r.d0 = r.d1 = r.d2 = (float2)(0.0f);
  for (int x = lo; x <= hi; ++x) {
    const float8 node = row[x];
    const float2 t = tx[x];
    const float2 wk = node.s01 + dtheta.x * node.s23 + dtheta.y * node.s45 + dtheta.z * node.s67;
    const float2 term = cmul(wk, t);
    r.s += term;
    r.sx += (float)x * term;
    r.d0 += cmul(node.s23, t);
    r.d1 += cmul(node.s45, t);
    r.d2 += cmul(node.s67, t);
  }
  return r;
}

inline void add_rotated_segments(RotatedSegment* a, const RotatedSegment b) {
  a->s += b.s;
  a->sx += b.sx;
  a->d0 += b.d0;
  a->d1 += b.d1;
  a->d2 += b.d2;
}

// A line's segment sums times p = ty[ky] tz[kz] into f, F and the rotation sums.
inline void add_rotated_line(Sums* sums, const RotatedSegment r, const float2 p, const short2 kyz,
                             const float real_weight, const int folded, const float4 inv_length) {
  const float2 term = real_weight * cmul(r.s, p);
  sums->f += (float2)(term.x, folded ? 0.0f : term.y);
#ifdef FORCE
  sums->force +=
      -TWO_PI * (float3)(real_weight * cmul(r.sx, p).y, (float)kyz.x * term.y, (float)kyz.y * term.y) * inv_length.xyz;
#endif
  sums->torque += real_weight * (float3)(cmul(r.d0, p).x, cmul(r.d1, p).x, cmul(r.d2, p).x);
}

// The x-lines of a product spectrum made for part 2 turned by R0 (kernels/rotated_product.cl,
// engine/query/rotated_product.h), at a pose R = exp([dtheta]x) R0 (docs/design.md "Exact
// rotation"): each box node holds float8 (W0, D_x, D_y, D_z), and the term is
//   W_k = W0_k + dtheta . D_k,   f = sum_k W_k e^{i phi},   phi = 2 pi w_k.tau,
// the energy to first order in the rotation since the product was made. The lines and
// extras are those of the translation-only sum (same selection, same folding), the extras
// given as int4 (box node, (kx, ky), (kz, code) as shorts, 0). Outputs as the other
// kernels, with the last three the rotation sums Re sum_k D_k e^{i phi} (from which the
// host makes the torque). The pose's s0-s2 hold dtheta (R itself enters only through tau).
__kernel __attribute__((reqd_work_group_size(WG_SIZE, 1, 1))) void rotated_lines(
    __global const float8* W, __global const int8* lines, __global const int4* extras, const int extra_count,
    const int folded, const float16 pose_arg, __global const float16* poses, const int pose_count, const int line_count,
    const int groups_per_pose, const int table_half, __global float* partials, const float4 inv_length) {
  const int group = get_group_id(0);
  const int pose = group / groups_per_pose;
  const int slice = group % groups_per_pose;
  const int lid = get_local_id(0);
  const float16 P = pose_count > 1 ? poses[pose] : pose_arg;
  const float3 dtheta = (float3)(P.s0, P.s1, P.s2);

  __local float2 tables[3 * (2 * MAX_HALF + 1)];
  __local float2* tx = tables + MAX_HALF;
  __local float2* ty = tx + (2 * MAX_HALF + 1);
  __local float2* tz = ty + (2 * MAX_HALF + 1);
  const int reach = min(table_half, MAX_HALF);
  for (int k = lid - reach; k <= reach; k += WG_SIZE) {
    tx[k] = axis_phase(k, P.s9, P.sc);
    ty[k] = axis_phase(k, P.sa, P.sd);
    tz[k] = axis_phase(k, P.sb, P.se);
  }
  barrier(CLK_LOCAL_MEM_FENCE);

  const float real_weight = folded ? 2.0f : 1.0f;
  Sums core = zero_sums(), band_a = zero_sums(), band_b = zero_sums();
  for (int l = slice * WG_SIZE + lid; l < line_count; l += groups_per_pose * WG_SIZE) {
    const int8 line = lines[l];
    const short2 kyz = as_short2(line.s1);
    __global const float8* row = W + line.s0;
    const float2 p = cmul(ty[kyz.x], tz[kyz.y]);
    // Core, band a and band b as in translation_lines.
    RotatedSegment a = rotated_segment(row, tx, dtheta, line.s4, line.s6 - 1),
                   b = rotated_segment(row, tx, dtheta, line.s2, line.s4 - 1);
    add_rotated_segments(&a, rotated_segment(row, tx, dtheta, line.s7 + 1, line.s5));
    add_rotated_segments(&b, rotated_segment(row, tx, dtheta, line.s5 + 1, line.s3));
    add_rotated_line(&core, rotated_segment(row, tx, dtheta, line.s6, line.s7), p, kyz, real_weight, folded,
                     inv_length);
    add_rotated_line(&band_a, a, p, kyz, real_weight, folded, inv_length);
    add_rotated_line(&band_b, b, p, kyz, real_weight, folded, inv_length);
  }
  if (slice == 0 && lid == 0) {
    for (int e = 0; e < extra_count; ++e) {
      const int4 mode = extras[e];
      const short2 kxy = as_short2(mode.y), kzc = as_short2(mode.z);
      const float8 node = W[mode.x];
      const float2 phase = cmul(tx[kxy.x], cmul(ty[kxy.y], tz[kzc.x]));
      const float2 wk = node.s01 + dtheta.x * node.s23 + dtheta.y * node.s45 + dtheta.z * node.s67;
      const float2 term = cmul(wk, phase);
      const float real = kzc.y == 1 ? 1.0f : -1.0f;
      Sums* to = kzc.y == 1 ? &band_b : &core;  // code 1: the pair m' cuts
      to->f += (float2)(real * term.x, term.y);
#ifdef FORCE
      to->force += -TWO_PI * real * term.y * convert_float3((int3)(kxy.x, kxy.y, kzc.x)) * inv_length.xyz;
#endif
      to->torque += real * (float3)(cmul(node.s23, phase).x, cmul(node.s45, phase).x, cmul(node.s67, phase).x);
    }
  }
  add_sums(&core, band_a);
  add_sums(&core, band_b);

  __local float scratch[SUMS_PER_GROUP * WG_SIZE];
  reduce_partials(scratch, lid, core, band_a, band_b, partials + SUMS_PER_GROUP * group);
}
#endif
