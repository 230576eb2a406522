// Unsigned distance from every grid point to the mesh: nearest-triangle search in the
// BVH, nearer child first, pruning subtrees whose box is farther than the best so far.
// (The sign comes from the winding number: docs/design.md, xi < 0 inside.)

__kernel void unsigned_distance(const long first_point, const long point_count, const float3 origin,
                                const float spacing, const int nx, const int ny, __global const BvhNode* nodes,
                                __global const float4* triangles, __global float* distance_out
#ifdef EXPLICIT_POINTS
                                ,
                                __global const float* point_x, __global const float* point_y,
                                __global const float* point_z
#endif
) {
  if (get_global_id(0) >= point_count) return;
#ifdef EXPLICIT_POINTS
  const size_t i = get_global_id(0);
  const float3 p = (float3)(point_x[i], point_y[i], point_z[i]);
#else
  const float3 p = grid_point(first_point + get_global_id(0), origin, spacing, nx, ny);
#endif
  float best2 = INFINITY;
  int stack[STACK_SIZE];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int n = stack[--top];
    __global const BvhNode* node = nodes + n;
    if (box_distance2(p, node->bbox_min.xyz, node->bbox_max.xyz) >= best2) continue;
    const int4 links = node->links;
    if (links.x < 0) {
      for (int t = links.y; t < links.y + links.z; ++t) {
        const float d2 =
            point_triangle_distance2(p, triangles[3 * t].xyz, triangles[3 * t + 1].xyz, triangles[3 * t + 2].xyz);
        best2 = fmin(best2, d2);
      }
      continue;
    }
    const int left = n + 1, right = links.x;
    const float dl = box_distance2(p, nodes[left].bbox_min.xyz, nodes[left].bbox_max.xyz);
    const float dr = box_distance2(p, nodes[right].bbox_min.xyz, nodes[right].bbox_max.xyz);
    // Push the farther child first so the nearer one is searched first.
    if (dl < dr) {
      if (dr < best2) stack[top++] = right;
      if (dl < best2) stack[top++] = left;
    } else {
      if (dl < best2) stack[top++] = left;
      if (dr < best2) stack[top++] = right;
    }
  }
  distance_out[get_global_id(0)] = sqrt(best2);
}
