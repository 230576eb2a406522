// Direct non-uniform DFT of a union of balls onto listed lattice modes (seed 001 eq. 23
// with the ball's analytic transform as the weight):
//   S(w) = sum_j Bhat(r_j, |w|) exp(-2 pi i w.y_j),  w = (k'_x / L_x, k'_y / L_y, k'_z / L_z),
// y_j the ball's centre relative to the spectrum's centre, Bhat the transform of the
// indicator of B(0, r): (4/3) pi r^3 * 3 (sin t - t cos t) / t^3 with t = 2 pi |w| r.
// One work item per mode; the phase is reduced to [-1/2, 1/2] cycles before cospi/sinpi
// (no sincos: Oclgrind's uninitialised-value check cannot follow its private pointer).

#define TWO_PI_F 6.28318530717958647f
#define FOUR_THIRDS_PI_F 4.18879020478639098f

inline float ball_shape(const float t) {
  const float t2 = t * t;
  if (t < 0.2f) return 1.0f - t2 * (0.1f - t2 * (1.0f / 280.0f - t2 * (1.0f / 15120.0f)));
  return 3.0f * (sin(t) - t * cos(t)) / (t2 * t);
}

__kernel void ball_ndft(__global const int4* modes, const int mode_count, __global const float4* balls,
                        const int ball_count, const float4 inverse_length, __global float2* out) {
  const int m = get_global_id(0);
  if (m >= mode_count) return;
  const int4 k = modes[m];
  const float4 w =
      (float4)((float)k.x * inverse_length.x, (float)k.y * inverse_length.y, (float)k.z * inverse_length.z, 0.0f);
  const float q = sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
  float2 sum = (float2)(0.0f, 0.0f);
  for (int j = 0; j < ball_count; ++j) {
    const float4 b = balls[j];
    const float r = b.w;
    const float weight = FOUR_THIRDS_PI_F * r * r * r * ball_shape(TWO_PI_F * q * r);
    float cycles = w.x * b.x + w.y * b.y + w.z * b.z;
    cycles -= rint(cycles);
    // exp(-2 pi i cycles), cycles in [-1/2, 1/2]
    sum += weight * (float2)(cospi(2.0f * cycles), -sinpi(2.0f * cycles));
  }
  out[m] = sum;
}
