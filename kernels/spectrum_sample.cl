// Shared by pose_query.cl and full_map.cl (prepended): complex arithmetic and the
// interpolation of a centred spectrum stored on the FFT grid (FFT order, periodic) at a
// fractional index u = w * L. Options: -D TRICUBIC (Catmull-Rom, 4 taps per axis;
// default trilinear, 2 taps), -D TRANSLATION_ONLY (no interpolation code at all).

#define TWO_PI 6.28318530717958647f

inline float2 cmul(const float2 a, const float2 b) { return (float2)(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x); }

#ifndef TRANSLATION_ONLY
inline int wrap(const int i, const int n) {
  const int r = i % n;
  return r < 0 ? r + n : r;
}

// Interpolation weights along one axis at fractional index u, and their derivatives
// d/du (the interpolant's slope): taps i0 + j.
#ifdef TRICUBIC
#define TAPS 4
inline int axis_weights(const float u, float* w, float* dw) {
  const float f = floor(u);
  const float t = u - f, t2 = t * t, t3 = t2 * t;
  // Catmull-Rom: interpolating, exact for quadratics, continuous slope.
  w[0] = 0.5f * (-t3 + 2.0f * t2 - t);
  w[1] = 0.5f * (3.0f * t3 - 5.0f * t2 + 2.0f);
  w[2] = 0.5f * (-3.0f * t3 + 4.0f * t2 + t);
  w[3] = 0.5f * (t3 - t2);
  dw[0] = 0.5f * (-3.0f * t2 + 4.0f * t - 1.0f);
  dw[1] = 0.5f * (9.0f * t2 - 10.0f * t);
  dw[2] = 0.5f * (-9.0f * t2 + 8.0f * t + 1.0f);
  dw[3] = 0.5f * (3.0f * t2 - 2.0f * t);
  return (int)f - 1;
}
#else
#define TAPS 2
inline int axis_weights(const float u, float* w, float* dw) {
  const float f = floor(u);
  w[1] = u - f;
  w[0] = 1.0f - w[1];
  dw[0] = -1.0f;
  dw[1] = 1.0f;
  return (int)f;
}
#endif
#endif

#ifndef TRANSLATION_ONLY
// One spectrum interpolated at fractional FFT index u (periodic).
inline float2 sample_spectrum(__global const float2* s, const int4 dims, const float3 u) {
  float wx[TAPS], wy[TAPS], wz[TAPS], dwx[TAPS], dwy[TAPS], dwz[TAPS];
  const int ix = axis_weights(u.x, wx, dwx), iy = axis_weights(u.y, wy, dwy), iz = axis_weights(u.z, wz, dwz);
  float2 v = (float2)(0.0f);
  for (int c = 0; c < TAPS; ++c) {
    const int z = wrap(iz + c, dims.z);
    for (int b = 0; b < TAPS; ++b) {
      const int zy = dims.y * z + wrap(iy + b, dims.y);
      for (int a = 0; a < TAPS; ++a) v += wx[a] * wy[b] * wz[c] * s[dims.x * zy + wrap(ix + a, dims.x)];
    }
  }
  return v;
}
#endif
