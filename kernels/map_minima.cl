// The local minima of a full translational map, found on the device (engine/maps/device_minima.h)
// so that a search reads back a short list per rotation instead of the whole map: the
// points engine/maps/map_minima.cpp finds on the host map, by the same rules.
//
// f: the complex inverse FFT of one map (engine/maps/full_map.cpp), E = -Re f, starting at
// element `offset` (a map of a batch in one buffer). Grid point
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
  const int j = i + n - n / 2;  // also for i = -1 and i = n, the neighbours past the faces
  return j >= n ? j - n : j;
}

// One work-item per grid point (x, y, z) = global id (0, 1, 2).
__kernel void map_local_minima(__global const float2* f, const int4 dims, const int4 lo, const int4 hi,
                               const uint capacity, __global uint* out, const ulong offset) {
  f += offset;
  const int x = (int)get_global_id(0), y = (int)get_global_id(1), z = (int)get_global_id(2);
  if (x < lo.x || x > hi.x || y < lo.y || y > hi.y || z < lo.z || z > hi.z) return;
  // FFT nodes of the point's column, row and plane and of their neighbours (0: -1, 2: +1).
  const int x0 = fft_node(x - 1, dims.x), x1 = fft_node(x, dims.x), x2 = fft_node(x + 1, dims.x);
  const int y0 = fft_node(y - 1, dims.y), y1 = fft_node(y, dims.y), y2 = fft_node(y + 1, dims.y);
  const int z0 = fft_node(z - 1, dims.z), z1 = fft_node(z, dims.z), z2 = fft_node(z + 1, dims.z);
  const int r11 = dims.x * (y1 + dims.y * z1);  // r<dy><dz>: the row's offset
  const float v = -f[x1 + r11].x;
  if (isinf(v)) {
    atomic_or(out + 2, 1u);
    return;
  }
  if (isnan(v)) return;
  // Neighbours inside the box on each side.
  const bool xl = (x > lo.x), xh = (x < hi.x), yl = (y > lo.y), yh = (y < hi.y), zl = (z > lo.z), zh = (z < hi.z);
  // A neighbour before the point in grid order beats it when lower or equal, one after it
  // when lower (NaN compares false: not counted).
#define BEFORE(inside, node) \
  if ((inside) && -f[node].x <= v) return;
#define AFTER(inside, node) \
  if ((inside) && -f[node].x < v) return;
  // The x neighbours first (most points have a lower one), then the faces, edges, corners.
  BEFORE(xl, x0 + r11)
  AFTER(xh, x2 + r11)
  const int r01 = dims.x * (y0 + dims.y * z1), r21 = dims.x * (y2 + dims.y * z1);
  const int r10 = dims.x * (y1 + dims.y * z0), r12 = dims.x * (y1 + dims.y * z2);
  BEFORE(yl, x1 + r01)
  AFTER(yh, x1 + r21)
  BEFORE(zl, x1 + r10)
  AFTER(zh, x1 + r12)
  BEFORE(yl && xl, x0 + r01)
  BEFORE(yl && xh, x2 + r01)
  AFTER(yh && xl, x0 + r21)
  AFTER(yh && xh, x2 + r21)
  if (zl) {
    const int r00 = dims.x * (y0 + dims.y * z0), r20 = dims.x * (y2 + dims.y * z0);
    BEFORE(xl, x0 + r10)
    BEFORE(xh, x2 + r10)
    BEFORE(yl, x1 + r00)
    BEFORE(yl && xl, x0 + r00)
    BEFORE(yl && xh, x2 + r00)
    BEFORE(yh, x1 + r20)
    BEFORE(yh && xl, x0 + r20)
    BEFORE(yh && xh, x2 + r20)
  }
  if (zh) {
    const int r02 = dims.x * (y0 + dims.y * z2), r22 = dims.x * (y2 + dims.y * z2);
    AFTER(xl, x0 + r12)
    AFTER(xh, x2 + r12)
    AFTER(yl, x1 + r02)
    AFTER(yl && xl, x0 + r02)
    AFTER(yl && xh, x2 + r02)
    AFTER(yh, x1 + r22)
    AFTER(yh && xl, x0 + r22)
    AFTER(yh && xh, x2 + r22)
  }
#undef BEFORE
#undef AFTER
  const uint g = (uint)(x + dims.x * (y + dims.y * z));
  if (v <= 0.0f) {
    const uint k = atomic_inc(out);
    if (k < capacity) {
      out[4 + 2 * k] = as_uint(v);
      out[5 + 2 * k] = g;
    }
  } else {
    atomic_min(out + 1, as_uint(v));
  }
}
