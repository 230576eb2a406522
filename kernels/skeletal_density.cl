// Skeletal density (seed 000 eq. 2 with the kernel of sec. 2.3; DESIGN.md):
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
// Triangles arrive pre-split to a fraction of the grid spacing (engine/triangle_refine.h),
// so MAX_SPLIT_DEPTH = 16 halvings reach ~2e-3 of the spacing, near the 1e-3 below which
// |xi| is clamped; a small split stack also keeps PoCL fast (measured: depth 40 is ~2x slower).
// Pieces still rejected at MAX_SPLIT_DEPTH use the exact solid angle times g(x_c),
// with error at most max|g(x) - g(x_c)| * |Omega|. The sum of all accepted bounds is
// written per point: a rigorous bound on |s_computed - s| (up to float rounding).

#ifndef MAX_SPLIT_DEPTH
#define MAX_SPLIT_DEPTH 16
#endif

typedef struct {
  float sigma, inv_sigma2, g0;
} Gaussian;

inline float gauss(const Gaussian g, const float x) { return g.g0 * exp(-0.5f * x * x * g.inv_sigma2); }

// Maxima of g, |g'| and |g''| over [lo, hi]. g'(x) = -x/s^2 g, g''(x) = (x^2/s^2 - 1)/s^2 g:
// |g'| peaks at |x| = s, |g''| at x = 0 and |x| = sqrt(3) s; otherwise at the ends.
inline float3 gauss_maxima(const Gaussian g, const float lo, const float hi) {
  const float glo = gauss(g, lo), ghi = gauss(g, hi);
  const bool has0 = lo <= 0.0f && hi >= 0.0f;
  const float s = g.sigma, s3 = 1.7320508f * g.sigma;
  float m0 = has0 ? g.g0 : fmax(glo, ghi);
  float m1 = fmax(fabs(lo) * glo, fabs(hi) * ghi) * g.inv_sigma2;
  if ((lo <= s && hi >= s) || (lo <= -s && hi >= -s)) m1 = g.g0 * 0.60653066f / s;  // e^-1/2
  float m2 = fmax(fabs(lo * lo * g.inv_sigma2 - 1.0f) * glo, fabs(hi * hi * g.inv_sigma2 - 1.0f) * ghi) * g.inv_sigma2;
  if (has0) m2 = fmax(m2, g.g0 * g.inv_sigma2);
  if ((lo <= s3 && hi >= s3) || (lo <= -s3 && hi >= -s3)) m2 = fmax(m2, 0.44626032f * g.g0 * g.inv_sigma2);  // 2e^-3/2
  return (float3)(m0, m1, m2);
}

// (1/2) K2 I, with K2 from the maxima m = (max g, max|g'|, max|g''|), for a cluster
// at distance d with radius r and second moment I (requires d > r).
inline float cluster_error_with(const float3 m, const float d, const float r, const float second, const float xi) {
  const float inv = 1.0f / (d - r);
  const float k2 = m.z * inv * inv / (xi * xi) + 5.0f * m.y * inv * inv * inv / xi + 6.0f * m.x * inv * inv * inv * inv;
  return 0.5f * k2 * second;
}

inline bool acceptable(const Gaussian g, const float err, const float area, const float dm, const float tolerance) {
  return err <= tolerance * g.g0 * area / (dm * dm);
}

// Error bound of a cluster if it is acceptable, else -1. The global maxima of g, |g'|,
// |g''| are tried first (no exp); the maxima over the cluster's x range only when needed.
inline float accepted_error(const Gaussian g, const float d, const float r, const float area, const float second,
                            const float xi, const float tolerance) {
  const float dm = d - r;
  const float3 global_max = (float3)(g.g0, g.g0 * 0.60653066f / g.sigma, g.g0 * g.inv_sigma2);
  float err = cluster_error_with(global_max, d, r, second, xi);
  if (acceptable(g, err, area, dm, tolerance)) return err;
  const float lo = dm / xi - 1.0f, hi = (d + r) / xi - 1.0f;
  // A range holding [0, sigma] has the global maxima (g at 0, |g'| at sigma, |g''| at 0):
  // the test would fail again, skip its two exp().
  if (lo <= 0.0f && hi >= g.sigma) return -1.0f;
  err = cluster_error_with(gauss_maxima(g, lo, hi), d, r, second, xi);
  return acceptable(g, err, area, dm, tolerance) ? err : -1.0f;
}

// One triangle, split adaptively. Adds to *s and *bound.
inline void integrate_triangle(const float3 p, const float xi, const Gaussian g, const float tolerance,
                               float3 a0, float3 b0, float3 c0, float* s, float* bound) {
  float3 sa[MAX_SPLIT_DEPTH + 1], sb[MAX_SPLIT_DEPTH + 1], sc[MAX_SPLIT_DEPTH + 1];
  int sdepth[MAX_SPLIT_DEPTH + 1];
  int top = 0;
  sa[0] = a0; sb[0] = b0; sc[0] = c0; sdepth[0] = 0;
  top = 1;
  while (top > 0) {
    --top;
    const float3 a = sa[top], b = sb[top], c = sc[top];
    const int depth = sdepth[top];
    const float3 cen = (a + b + c) * (1.0f / 3.0f);
    const float3 an = 0.5f * cross(b - a, c - a);  // A n
    const float area = length(an);
    if (area == 0.0f) continue;
    const float ra2 = dot(a - cen, a - cen), rb2 = dot(b - cen, b - cen), rc2 = dot(c - cen, c - cen);
    const float r = sqrt(fmax(fmax(ra2, rb2), rc2));
    const float3 u = cen - p;
    const float d = length(u);
    const float xc = d / xi - 1.0f;
    if (d > r) {
      // Second moment of the piece about its centroid, grown by a float step.
      const float second = area * (ra2 + rb2 + rc2) * (1.0f / 12.0f) * 1.00001f;
      const float err = accepted_error(g, d, r, area, second, xi, tolerance);
      if (err >= 0.0f) {
        *s += gauss(g, xc) * dot(u, an) / (d * d * d);  // midpoint rule, M = 0
        *bound += err;
        continue;
      }
    }
    if (depth >= MAX_SPLIT_DEPTH) {
      // Exact solid angle times g at the centroid: error <= max|g(x) - g(x_c)| |Omega|.
      const float omega = triangle_solid_angle(p, a, b, c);
      const float lo = fmax(d - r, 0.0f) / xi - 1.0f, hi = (d + r) / xi - 1.0f;
      const float gc = gauss(g, xc);
      float dev = fmax(fabs(gauss(g, lo) - gc), fabs(gauss(g, hi) - gc));
      if (lo <= 0.0f && hi >= 0.0f) dev = fmax(dev, g.g0 - gc);
      *s += gc * omega;
      *bound += dev * fabs(omega);
      continue;
    }
    // Split the longest edge; the two halves go on the stack.
    const float lab = dot(b - a, b - a), lbc = dot(c - b, c - b), lca = dot(a - c, a - c);
    float3 x0, x1, x2;  // x0-x1 is the longest edge
    if (lab >= lbc && lab >= lca) { x0 = a; x1 = b; x2 = c; }
    else if (lbc >= lca) { x0 = b; x1 = c; x2 = a; }
    else { x0 = c; x1 = a; x2 = b; }
    const float3 mid = 0.5f * (x0 + x1);
    sa[top] = x0; sb[top] = mid; sc[top] = x2; sdepth[top] = depth + 1; ++top;
    sa[top] = mid; sb[top] = x1; sc[top] = x2; sdepth[top] = depth + 1; ++top;
  }
}

__kernel void skeletal_density(const long first_point, const long point_count, const float3 origin,
                               const float spacing, const int nx, const int ny,
                               __global const BvhNode* nodes, __global const float4* triangles,
                               __global const float* distance, const float min_distance,
                               const float sigma, const float tolerance, const int triangle_count,
                               __global float* density_out, __global float* bound_out) {
  const long gid = get_global_id(0);
  if (gid >= point_count) return;
  const float3 p = grid_point(first_point + gid, origin, spacing, nx, ny);
  const float xi = fmax(distance[gid], min_distance);
  Gaussian g;
  g.sigma = sigma;
  g.inv_sigma2 = 1.0f / (sigma * sigma);
  g.g0 = 0.39894228f / sigma;  // 1/(sqrt(2 pi) sigma)
  float s = 0.0f, bound = 0.0f;
#ifdef BRUTE_FORCE
  // The paper's O(m n) sum (seed 000 sec. 3.1): every triangle, split adaptively, no
  // hierarchy. `nodes` is unused; `triangle_count` triangles are read in order.
  for (int t = 0; t < triangle_count; ++t)
    integrate_triangle(p, xi, g, tolerance, triangles[3 * t].xyz, triangles[3 * t + 1].xyz, triangles[3 * t + 2].xyz,
                       &s, &bound);
#else
  int stack[STACK_SIZE];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int n = stack[--top];
    __global const BvhNode* node = nodes + n;
    const float3 u = node->centroid.xyz - p;
    const float d = length(u);
    const float r = node->bbox_max.w, area = node->bbox_min.w;
    if (d > r && area > 0.0f) {
      const float err = accepted_error(g, d, r, area, node->centroid.w, xi, tolerance);
      if (err >= 0.0f) {
        const float inv_d = 1.0f / d;
        const float inv_d3 = inv_d * inv_d * inv_d;
        const float3 u_hat = u * inv_d;
        const float xc = d / xi - 1.0f;
        const float gc = gauss(g, xc);
        const float dgc = -xc * g.inv_sigma2 * gc;  // g'(x_c)
        const float3 mu = (float3)(dot(node->moment[0].xyz, u_hat), dot(node->moment[1].xyz, u_hat),
                                   dot(node->moment[2].xyz, u_hat));
        s += gc * (dot(u, node->area_normal.xyz) * inv_d3 + first_order_term(u_hat, inv_d3, node)) +
             dgc / xi * dot(u, mu) * inv_d3;
        bound += err;
        continue;
      }
    }
    const int4 links = node->links;
    if (links.x < 0) {
      for (int t = links.y; t < links.y + links.z; ++t)
        integrate_triangle(p, xi, g, tolerance, triangles[3 * t].xyz, triangles[3 * t + 1].xyz,
                           triangles[3 * t + 2].xyz, &s, &bound);
      continue;
    }
    stack[top++] = links.x;
    stack[top++] = n + 1;
  }
#endif
  density_out[gid] = s;
  bound_out[gid] = bound;
}
