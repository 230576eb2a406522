// Generalized winding number w(p) = (1/4pi) sum of signed triangle solid angles
// (seed 000 sec. 2.3: the inverse-square kernel of eq. 2; 1 inside, 0 outside).
// Fast winding numbers (Barill et al. 2018): a node whose ball (centre c, radius r) is
// far from p contributes its first-order expansion
//     Omega ~ F(c).N + sum_ij J_ij M_ij,   F(q) = (q - p)/|q - p|^3,
// with the remainder bounded by (1/2) max|d^2F/dt^2| r^2 A <= 3 r^2 A / (D - r)^4
// (the directional second derivative of F is at most 6/|q - p|^4). A node is expanded
// when that bound is at most `tolerance` times its solid-angle bound A/(D - r)^2;
// otherwise its children are visited, and leaves are summed exactly.
// Output: w and its error bound (sum of the accepted remainders / 4pi).
// With -D POINT_LIST the points are grid indices point_ids[first_point + i] (the seeds
// of engine/fields/winding_propagation.h) instead of the range first_point + i; with
// -D EXPLICIT_POINTS (and no POINT_LIST) the chunk's points are read from point_x/y/z.

__kernel void winding_number(const long first_point, const long point_count, const float3 origin, const float spacing,
                             const int nx, const int ny, __global const BvhNode* nodes,
                             __global const float4* triangles, const float tolerance, __global float* winding_out,
                             __global float* bound_out
#ifdef POINT_LIST
                             ,
                             __global const long* point_ids
#endif
#ifdef EXPLICIT_POINTS
                             ,
                             __global const float* point_x, __global const float* point_y, __global const float* point_z
#endif
) {
  if (get_global_id(0) >= point_count) return;
#if defined(EXPLICIT_POINTS)
  const size_t i = get_global_id(0);
  const float3 p = (float3)(point_x[i], point_y[i], point_z[i]);
#elif defined(POINT_LIST)
  const float3 p = grid_point(point_ids[first_point + get_global_id(0)], origin, spacing, nx, ny);
#else
  const float3 p = grid_point(first_point + get_global_id(0), origin, spacing, nx, ny);
#endif
  float omega = 0.0f, bound = 0.0f;
  int stack[STACK_SIZE];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int n = stack[--top];
    __global const BvhNode* node = nodes + n;
    const float3 u = node->centroid.xyz - p;
    const float d = length(u);
    const float r = node->bbox_max.w, area = node->bbox_min.w;
    const float dm = d - r;
    // Accept when D > 2r and 3 r^2 / (D - r)^2 <= tolerance.
    if (dm > r && 3.0f * r * r <= tolerance * dm * dm) {
      const float inv_d = 1.0f / d;
      const float inv_d3 = inv_d * inv_d * inv_d;
      const float3 u_hat = u * inv_d;
      omega += dot(u, node->area_normal.xyz) * inv_d3 + first_order_term(u_hat, inv_d3, node);
      bound += 3.0f * r * r * area / (dm * dm * dm * dm);
      continue;
    }
    const int4 links = node->links;
    if (links.x < 0) {
      for (int t = links.y; t < links.y + links.z; ++t)
        omega += triangle_solid_angle(p, triangles[3 * t].xyz, triangles[3 * t + 1].xyz, triangles[3 * t + 2].xyz);
      continue;
    }
    stack[top++] = links.x;
    stack[top++] = n + 1;
  }
  const float inv_4pi = 0.0795774715f;
  winding_out[get_global_id(0)] = omega * inv_4pi;
  bound_out[get_global_id(0)] = bound * inv_4pi;
}
