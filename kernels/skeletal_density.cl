// Skeletal density (seed 000 eq. 2 with the kernel of sec. 2.3; docs/design.md):
//     s(p) = integral over the boundary of g_sigma(eta/|xi| - 1) dOmega(q),
//     dOmega = F(q).n dA,  F(q) = (q - p)/|q - p|^3,  eta = |q - p|,
// g_sigma the normalized Gaussian, |xi| the distance from p to the mesh (input).
// Outward normals make s > 0 inside and s < 0 outside.
//
// Quadrature with a bounded error. A cluster (a BVH node, or a piece of a triangle)
// with centroid c, ball radius r, area A and moments N, M is replaced by the
// first-order expansion of K(q) = g(x(q)) F(q) about c (x = eta/|xi| - 1, u = c - p,
// D = |u|):
//     integral ~ g(x_c) [F(c).N + sum_ij J_ij M_ij] + g'(x_c)/|xi| F(c).(M u^)
// (a single flat piece has M = 0: the midpoint rule, also second order). Along any
// segment the second derivative of K is at most
//     K2 = |g''|/(|xi|^2 eta^2) + 5|g'|/(|xi| eta^3) + 6 g/eta^4,   eta >= D - r,
// with the maxima of g, |g'|, |g''| taken over the cluster's x range, so the Taylor
// remainder at q is at most (1/2) K2 |q - c|^2 and the error at most (1/2) K2 I, with
// I = integral of |q - c|^2 dA the cluster's second moment (stored per node; for a
// triangle piece (A/12) sum_i |v_i - c|^2 <= r^2 A / 4). A cluster is accepted when that bound is at most
// tolerance * g(0) * A/(D - r)^2 (a relative error on its solid-angle bound);
// otherwise nodes open their children and triangles are split at their longest edge.
// Triangles arrive pre-split to a fraction of the grid spacing (mesh/triangle_refine.h),
// so MAX_SPLIT_DEPTH = 16 halvings reach ~2e-3 of the spacing, near the 1e-3 below which
// |xi| is clamped; a small split stack also keeps PoCL fast (measured: depth 40 is ~2x slower).
// Pieces still rejected at MAX_SPLIT_DEPTH use the exact solid angle times g(x_c),
// with error at most max|g(x) - g(x_c)| * |Omega|. The sum of all accepted bounds is
// written per point: a rigorous bound on |s_computed - s| (up to float rounding).
//
// Point packets (-D LANES=1, 4, 8 or 16). A work item evaluates LANES grid points at
// once, in SIMD: the points of one small brick of the grid (engine/fields/descriptors.cpp
// orders them), which mostly accept and open the same clusters. Every cluster and
// triangle piece is tested per lane; a lane adds the clusters it accepts and goes on
// only into those it rejects (a mask travels with each stack entry), so each point sums
// exactly what it would alone, in the same order. A lane whose point id is negative is
// padding (a brick cut by the grid's edge) and does nothing. LANES=1 is the plain
// per-point kernel (GPUs, where a work item per point is what the hardware wants).

#ifndef MAX_SPLIT_DEPTH
#define MAX_SPLIT_DEPTH 16
#endif
#ifndef LANES
#define LANES 1
#endif

// A value per lane (real_v), a lane mask (mask_v: relational results, all bits set in a
// true vector lane, 1 in a scalar) and the point ids (long_v).
#if LANES == 1
#define real_v float
#define mask_v int
#define long_v long
#define ANY(m) ((m) != 0)
#define LOAD_V(i, p) ((p)[i])
#define STORE_V(v, i, p) ((p)[i] = (v))
#define convert_real_v convert_float
#define convert_mask_v convert_int
#elif LANES == 4 || LANES == 8 || LANES == 16
#define VEC_(t, n) t##n
#define VEC(t, n) VEC_(t, n)
#define real_v VEC(float, LANES)
#define mask_v VEC(int, LANES)
#define long_v VEC(long, LANES)
#define ANY(m) any(m)
#define LOAD_V VEC(vload, LANES)
#define STORE_V VEC(vstore, LANES)
#define convert_real_v VEC(convert_float, LANES)
#define convert_mask_v VEC(convert_int, LANES)
#else
#error "LANES must be 1, 4, 8 or 16"
#endif
// Lanes of m not in a (either mask kind: a true lane is 1 or all bits).
#define AND_NOT(m, a) ((m) & ~(a))

typedef struct {
  float sigma, inv_sigma2, g0;
} Gaussian;

// The grid points of a packet, one per lane.
typedef struct {
  real_v x, y, z, xi;  // position and clamped |xi|
} Points;

inline real_v gauss(const Gaussian g, const real_v x) { return g.g0 * exp(-0.5f * x * x * g.inv_sigma2); }

// (1/2) K2 I, with K2 from the maxima (m0, m1, m2) = (max g, max|g'|, max|g''|), for a
// cluster at distance d with radius r and second moment I (requires d > r).
inline real_v cluster_error_with(const real_v m0, const real_v m1, const real_v m2, const real_v d, const float r,
                                 const float second, const real_v xi) {
  const real_v inv = 1.0f / (d - r);
  const real_v k2 = m2 * inv * inv / (xi * xi) + 5.0f * m1 * inv * inv * inv / xi + 6.0f * m0 * inv * inv * inv * inv;
  return 0.5f * k2 * second;
}

inline mask_v acceptable(const Gaussian g, const real_v err, const float area, const real_v dm, const float tolerance) {
  return err <= tolerance * g.g0 * area / (dm * dm);
}

// Error bound of a cluster per lane, or -1 where it is not acceptable. The global maxima
// of g, |g'|, |g''| are tried first (no exp); the maxima over the cluster's x range only
// for the lanes that need them. Lanes outside `active` may hold anything.
inline real_v accepted_error(const Gaussian g, const mask_v active, const real_v d, const float r, const float area,
                             const float second, const real_v xi, const float tolerance) {
  const real_v dm = d - r;
  real_v err = cluster_error_with((real_v)(g.g0), (real_v)(g.g0 * 0.60653066f / g.sigma), (real_v)(g.g0 * g.inv_sigma2),
                                  d, r, second, xi);
  const mask_v ok = acceptable(g, err, area, dm, tolerance);
  err = select((real_v)(-1.0f), err, ok);
  // Maxima over [lo, hi]: g'(x) = -x/s^2 g, g''(x) = (x^2/s^2 - 1)/s^2 g; |g'| peaks at
  // |x| = s, |g''| at x = 0 and |x| = sqrt(3) s; otherwise at the ends. A range holding
  // [0, sigma] has the global maxima (g at 0, |g'| at sigma, |g''| at 0): skip it.
  const real_v lo = dm / xi - 1.0f, hi = (d + r) / xi - 1.0f;
  const mask_v retry = AND_NOT(AND_NOT(active, ok), (lo <= 0.0f) & (hi >= g.sigma));
  if (!ANY(retry)) return err;
  const real_v glo = gauss(g, lo), ghi = gauss(g, hi);
  const float s = g.sigma, s3 = 1.7320508f * g.sigma;
  const mask_v has0 = (lo <= 0.0f) & (hi >= 0.0f);
  const real_v m0 = select(fmax(glo, ghi), (real_v)(g.g0), has0);
  real_v m1 = fmax(fabs(lo) * glo, fabs(hi) * ghi) * g.inv_sigma2;
  m1 = select(m1, (real_v)(g.g0 * 0.60653066f / s), ((lo <= s) & (hi >= s)) | ((lo <= -s) & (hi >= -s)));  // e^-1/2
  real_v m2 = fmax(fabs(lo * lo * g.inv_sigma2 - 1.0f) * glo, fabs(hi * hi * g.inv_sigma2 - 1.0f) * ghi) * g.inv_sigma2;
  m2 = select(m2, fmax(m2, g.g0 * g.inv_sigma2), has0);
  m2 = select(m2, fmax(m2, 0.44626032f * g.g0 * g.inv_sigma2),
              ((lo <= s3) & (hi >= s3)) | ((lo <= -s3) & (hi >= -s3)));  // 2e^-3/2
  const real_v err2 = cluster_error_with(m0, m1, m2, d, r, second, xi);
  return select(err, err2, retry & acceptable(g, err2, area, dm, tolerance));
}

// Signed solid angle of triangle (a, b, c) seen from each lane's point (the per-lane
// form of geometry.cl's triangle_solid_angle, same formula and same edge-on rule).
inline real_v triangle_solid_angle_v(const Points p, const float3 va, const float3 vb, const float3 vc) {
  const real_v ax = va.x - p.x, ay = va.y - p.y, az = va.z - p.z;
  const real_v bx = vb.x - p.x, by = vb.y - p.y, bz = vb.z - p.z;
  const real_v cx = vc.x - p.x, cy = vc.y - p.y, cz = vc.z - p.z;
  const real_v la = sqrt(ax * ax + ay * ay + az * az), lb = sqrt(bx * bx + by * by + bz * bz),
               lc = sqrt(cx * cx + cy * cy + cz * cz);
  const real_v det = ax * (by * cz - bz * cy) + ay * (bz * cx - bx * cz) + az * (bx * cy - by * cx);
  const real_v div = la * lb * lc + (ax * bx + ay * by + az * bz) * lc + (ax * cx + ay * cy + az * cz) * lb +
                     (bx * cx + by * cy + bz * cz) * la;
  return select(2.0f * atan2(det, div), (real_v)(0.0f), fabs(det) <= 1e-6f * la * lb * lc);
}

// One triangle for the lanes in `active`, split adaptively. Adds to *s and *bound.
inline void integrate_triangle(const Points p, const mask_v active, const Gaussian g, const float tolerance, float3 a0,
                               float3 b0, float3 c0, real_v* s, real_v* bound) {
  float3 sa[MAX_SPLIT_DEPTH + 1], sb[MAX_SPLIT_DEPTH + 1], sc[MAX_SPLIT_DEPTH + 1];
  int sdepth[MAX_SPLIT_DEPTH + 1];
  mask_v smask[MAX_SPLIT_DEPTH + 1];
  sa[0] = a0;
  sb[0] = b0;
  sc[0] = c0;
  sdepth[0] = 0;
  smask[0] = active;
  int top = 1;
  while (top > 0) {
    --top;
    const float3 a = sa[top], b = sb[top], c = sc[top];
    const int depth = sdepth[top];
    const mask_v live = smask[top];
    const float3 cen = (a + b + c) * (1.0f / 3.0f);
    const float3 an = 0.5f * cross(b - a, c - a);  // A n
    const float area = length(an);
    if (area == 0.0f) continue;
    const float ra2 = dot(a - cen, a - cen), rb2 = dot(b - cen, b - cen), rc2 = dot(c - cen, c - cen);
    const float r = sqrt(fmax(fmax(ra2, rb2), rc2));
    const real_v ux = cen.x - p.x, uy = cen.y - p.y, uz = cen.z - p.z;
    const real_v d = sqrt(ux * ux + uy * uy + uz * uz);
    const real_v xc = d / p.xi - 1.0f;
    const mask_v outside = live & (d > r);
    mask_v rest = live;
    if (ANY(outside)) {
      // Second moment of the piece about its centroid, grown by a float step.
      const float second = area * (ra2 + rb2 + rc2) * (1.0f / 12.0f) * 1.00001f;
      const real_v err = accepted_error(g, outside, d, r, area, second, p.xi, tolerance);
      const mask_v take = outside & (err >= 0.0f);
      if (ANY(take)) {
        const real_v term = gauss(g, xc) * (ux * an.x + uy * an.y + uz * an.z) / (d * d * d);  // midpoint rule, M = 0
        *s += select((real_v)(0.0f), term, take);
        *bound += select((real_v)(0.0f), err, take);
        rest = AND_NOT(live, take);
        if (!ANY(rest)) continue;
      }
    }
    if (depth >= MAX_SPLIT_DEPTH) {
      // Exact solid angle times g at the centroid: error <= max|g(x) - g(x_c)| |Omega|.
      const real_v omega = triangle_solid_angle_v(p, a, b, c);
      const real_v lo = fmax(d - r, 0.0f) / p.xi - 1.0f, hi = (d + r) / p.xi - 1.0f;
      const real_v gc = gauss(g, xc);
      real_v dev = fmax(fabs(gauss(g, lo) - gc), fabs(gauss(g, hi) - gc));
      dev = select(dev, fmax(dev, g.g0 - gc), (lo <= 0.0f) & (hi >= 0.0f));
      *s += select((real_v)(0.0f), gc * omega, rest);
      *bound += select((real_v)(0.0f), dev * fabs(omega), rest);
      continue;
    }
    // Split the longest edge; the two halves go on the stack for the lanes still open.
    const float lab = dot(b - a, b - a), lbc = dot(c - b, c - b), lca = dot(a - c, a - c);
    float3 x0, x1, x2;  // x0-x1 is the longest edge
    if (lab >= lbc && lab >= lca) {
      x0 = a;
      x1 = b;
      x2 = c;
    } else if (lbc >= lca) {
      x0 = b;
      x1 = c;
      x2 = a;
    } else {
      x0 = c;
      x1 = a;
      x2 = b;
    }
    const float3 mid = 0.5f * (x0 + x1);
    sa[top] = x0;
    sb[top] = mid;
    sc[top] = x2;
    sdepth[top] = depth + 1;
    smask[top] = rest;
    ++top;
    sa[top] = mid;
    sb[top] = x1;
    sc[top] = x2;
    sdepth[top] = depth + 1;
    smask[top] = rest;
    ++top;
  }
}

// Work item i evaluates the LANES points point_ids[first_item + LANES i + lane] (a
// negative id: padding); distance_in and the outputs hold the chunk's items in that order,
// and so do point_x/y/z with -D EXPLICIT_POINTS (the points' coordinates, read instead of
// the grid's).
__kernel void skeletal_density(const long first_item, const long item_count, const float3 origin, const float spacing,
                               const int nx, const int ny, __global const BvhNode* nodes,
                               __global const float4* triangles, __global const float* distance_in,
                               const float min_distance, const float sigma, const float tolerance,
                               const int triangle_count, __global float* density_out, __global float* bound_out,
                               __global const long* point_ids
#ifdef EXPLICIT_POINTS
                               ,
                               __global const float* point_x, __global const float* point_y,
                               __global const float* point_z
#endif
) {
  const long gid = get_global_id(0);
  if (gid * LANES >= item_count) return;
  const long_v id = LOAD_V(0, point_ids + first_item + gid * LANES);
  const mask_v valid = convert_mask_v(id >= 0);
  Points p;
#ifdef EXPLICIT_POINTS
  p.x = LOAD_V(gid, point_x);
  p.y = LOAD_V(gid, point_y);
  p.z = LOAD_V(gid, point_z);
#else
  const long_v cell = max(id, (long_v)(0));
  p.x = origin.x + spacing * convert_real_v(cell % nx);
  p.y = origin.y + spacing * convert_real_v((cell / nx) % ny);
  p.z = origin.z + spacing * convert_real_v(cell / ((long)nx * ny));
#endif
  p.xi = fmax(LOAD_V(gid, distance_in), min_distance);
  Gaussian g;
  g.sigma = sigma;
  g.inv_sigma2 = 1.0f / (sigma * sigma);
  g.g0 = 0.39894228f / sigma;  // 1/(sqrt(2 pi) sigma)
  real_v s = 0.0f, bound = 0.0f;
#ifdef BRUTE_FORCE
  // The paper's O(m n) sum (seed 000 sec. 3.1): every triangle, split adaptively, no
  // hierarchy. `nodes` is unused; `triangle_count` triangles are read in order.
  for (int t = 0; t < triangle_count; ++t)
    integrate_triangle(p, valid, g, tolerance, triangles[3 * t].xyz, triangles[3 * t + 1].xyz, triangles[3 * t + 2].xyz,
                       &s, &bound);
#else
  int stack[STACK_SIZE];
  mask_v stack_mask[STACK_SIZE];
  int top = 0;
  stack[top] = 0;
  stack_mask[top++] = valid;
  while (top > 0) {
    --top;
    const int n = stack[top];
    const mask_v live = stack_mask[top];
    __global const BvhNode* node = nodes + n;
    const float3 c = node->centroid.xyz;
    const real_v ux = c.x - p.x, uy = c.y - p.y, uz = c.z - p.z;
    const real_v d = sqrt(ux * ux + uy * uy + uz * uz);
    const float r = node->bbox_max.w, area = node->bbox_min.w;
    mask_v rest = live;
    const mask_v outside = live & (d > r);
    if (area > 0.0f && ANY(outside)) {
      const real_v err = accepted_error(g, outside, d, r, area, node->centroid.w, p.xi, tolerance);
      const mask_v take = outside & (err >= 0.0f);
      if (ANY(take)) {
        const real_v inv_d = 1.0f / d;
        const real_v inv_d3 = inv_d * inv_d * inv_d;
        const real_v hx = ux * inv_d, hy = uy * inv_d, hz = uz * inv_d;  // u^
        const real_v xc = d / p.xi - 1.0f;
        const real_v gc = gauss(g, xc);
        const real_v dgc = -xc * g.inv_sigma2 * gc;  // g'(x_c)
        const float3 m0 = node->moment[0].xyz, m1 = node->moment[1].xyz, m2 = node->moment[2].xyz;
        const float3 an = node->area_normal.xyz;
        const real_v mu0 = m0.x * hx + m0.y * hy + m0.z * hz;  // M u^
        const real_v mu1 = m1.x * hx + m1.y * hy + m1.z * hz;
        const real_v mu2 = m2.x * hx + m2.y * hy + m2.z * hz;
        // sum_ij J_ij M_ij, J = (I - 3 u^ u^T)/|u|^3 (geometry.cl, first_order_term).
        const real_v first = (m0.x + m1.y + m2.z - 3.0f * (hx * mu0 + hy * mu1 + hz * mu2)) * inv_d3;
        const real_v term = gc * ((ux * an.x + uy * an.y + uz * an.z) * inv_d3 + first) +
                            dgc / p.xi * (ux * mu0 + uy * mu1 + uz * mu2) * inv_d3;
        s += select((real_v)(0.0f), term, take);
        bound += select((real_v)(0.0f), err, take);
        rest = AND_NOT(live, take);
        if (!ANY(rest)) continue;
      }
    }
    const int4 links = node->links;
    if (links.x < 0) {
      for (int t = links.y; t < links.y + links.z; ++t)
        integrate_triangle(p, rest, g, tolerance, triangles[3 * t].xyz, triangles[3 * t + 1].xyz,
                           triangles[3 * t + 2].xyz, &s, &bound);
      continue;
    }
    stack[top] = links.x;
    stack_mask[top++] = rest;
    stack[top] = n + 1;
    stack_mask[top++] = rest;
  }
#endif
  STORE_V(s, gid, density_out);
  STORE_V(bound, gid, bound_out);
}
