// The local minima of a full translational map, found on the device (engine/device_minima.h)
// so that a search reads back a short list per rotation instead of the whole map: the
// points engine/map_minima.cpp finds on the host map, by the same rules.
//
// f: clFFT's complex inverse FFT of one map (engine/full_map.cpp), E = -Re f. Grid point
// (x, y, z) in regular order (translation index x - N/2 per axis) is FFT node
// (x + N - N/2) mod N per axis. Points outside lo..hi (per axis, inclusive: the aliasing
// mask) have E = NaN.
//
// A point is a minimum when E is finite and none of its 26 neighbours is lower, or equal
// at a lower grid index (on a plateau the first point in grid order counts); NaN
// neighbours and those beyond the grid do not count. Minima with E <= 0 go to the list:
// E < 0 are the map's minima, E = 0 (either sign) may decide its lowest value. Of the
// others only the lowest E goes to out[1]. The map's lowest finite E is at a minimum by
// these rules (its first point in grid order: no neighbour is lower, none before it is
// equal), so it is in the list or in out[1]. A point with E = +-inf sets out[2]: then the
// lowest finite E need not be at a minimum, and the host takes the whole map instead.
//
// out: [0] the number of minima with E <= 0 (it may exceed `capacity`: entries past it are
// not written), [1] as_uint of the lowest E > 0 at a minimum (as_uint orders positive
// floats; 0xffffffff: none), [2] nonzero when an infinity was seen, [3] unused; then per
// list entry (as_uint(E), grid index), in no particular order.

inline int fft_node(const int i, const int n) {
  const int j = i + n - n / 2;
  return j >= n ? j - n : j;
}

__kernel void map_local_minima(__global const float2* f, const int4 dims, const int4 lo, const int4 hi,
                               const uint capacity, __global uint* out) {
  const int g = (int)get_global_id(0);
  if (g >= dims.x * dims.y * dims.z) return;
  const int x = g % dims.x, y = (g / dims.x) % dims.y, z = g / (dims.x * dims.y);
  if (x < lo.x || x > hi.x || y < lo.y || y > hi.y || z < lo.z || z > hi.z) return;
  const int row = dims.x * (fft_node(y, dims.y) + dims.y * fft_node(z, dims.z));
  const float v = -f[fft_node(x, dims.x) + row].x;
  if (isinf(v)) {
    atomic_or(out + 2, 1u);
    return;
  }
  if (isnan(v)) return;
  // Cheap rejections first, as on the host: most points have a lower x neighbour.
  if (x > lo.x && -f[fft_node(x - 1, dims.x) + row].x <= v) return;
  if (x < hi.x && -f[fft_node(x + 1, dims.x) + row].x < v) return;
  for (int dz = -1; dz <= 1; ++dz) {
    const int zz = z + dz;
    if (zz < lo.z || zz > hi.z) continue;
    for (int dy = -1; dy <= 1; ++dy) {
      const int yy = y + dy;
      if (yy < lo.y || yy > hi.y) continue;
      const int r = dims.x * (fft_node(yy, dims.y) + dims.y * fft_node(zz, dims.z));
      for (int dx = -1; dx <= 1; ++dx) {
        const int xx = x + dx;
        if (xx < lo.x || xx > hi.x || (dx == 0 && dy == 0 && dz == 0)) continue;
        const float w = -f[fft_node(xx, dims.x) + r].x;  // NaN compares false: not counted
        const int n = g + dx + dims.x * (dy + dims.y * dz);
        if (w < v || (w == v && n < g)) return;
      }
    }
  }
  if (v <= 0.0f) {
    const uint k = atomic_inc(out);
    if (k < capacity) {
      out[4 + 2 * k] = as_uint(v);
      out[5 + 2 * k] = (uint)g;
    }
  } else {
    atomic_min(out + 1, as_uint(v));
  }
}
