#include "engine/fields/descriptors.h"

#include <chrono>
#include <climits>
#include <cmath>

#include "core/progress.h"
#include "engine/fields/triangle_bvh.h"
#include "engine/fields/winding_propagation.h"
#include "engine/runtime/kernel_sources.h"
#include "mesh/triangle_refine.h"
#include "snapfit/error.h"

namespace snapfit {
namespace {

// A chunk-sized device buffer tied to a whole-grid host array.
struct ChunkIo {
  cl::Buffer buffer;
  std::vector<float>* host;
};

// Runs `kernel` over `count` items (the grid points, or a list of them) chunk by chunk,
// `lanes` items per work item (count and the chunk size are multiples of it). Arguments
// 0..5 (first item, item count, origin, spacing, nx, ny) are set here, the rest by the
// caller beforehand. Inputs are written from their host arrays before each launch,
// outputs read back after it. Progress is reported in grid points (a list of items
// counts as the whole grid, in proportion).
void run_pass(const ComputeContext& ctx, const GridSpec& grid, const DescriptorOptions& options, cl::Kernel& kernel,
              const std::vector<ChunkIo>& inputs, const std::vector<ChunkIo>& outputs, const std::string& pass,
              std::size_t count, std::size_t chunk_items, std::size_t lanes = 1) {
  const cl_float3 origin{{static_cast<float>(grid.origin.x()), static_cast<float>(grid.origin.y()),
                          static_cast<float>(grid.origin.z()), 0.0f}};
  kernel.setArg(2, origin);
  kernel.setArg(3, static_cast<float>(grid.spacing));
  kernel.setArg(4, static_cast<cl_int>(grid.dims.x()));
  kernel.setArg(5, static_cast<cl_int>(grid.dims.y()));
  const std::uint64_t points = grid.count();
  auto report = [&](std::size_t done) {
    if (options.progress) options.progress(pass, done == count ? points : done * points / count, points);
  };
  report(0);  // starts the clock before the first chunk
  for (std::size_t first = 0; first < count; first += chunk_items) {
    const std::size_t n = std::min(chunk_items, count - first);
    kernel.setArg(0, static_cast<cl_long>(first));
    kernel.setArg(1, static_cast<cl_long>(n));
    for (const ChunkIo& in : inputs)
      ctx.queue.enqueueWriteBuffer(in.buffer, CL_FALSE, 0, sizeof(float) * n, in.host->data() + first);
    std::size_t global = (n + lanes - 1) / lanes;
    cl::NDRange local = cl::NullRange;
    if (options.work_group_size > 0) {
      global = (global + options.work_group_size - 1) / options.work_group_size * options.work_group_size;
      local = cl::NDRange(options.work_group_size);
    }
    ctx.queue.enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(global), local);
    for (const ChunkIo& out : outputs)
      ctx.queue.enqueueReadBuffer(out.buffer, CL_FALSE, 0, sizeof(float) * n, out.host->data() + first);
    ctx.queue.finish();
    report(first + n);
  }
}

// Points per work item of the density kernel: options.density_lanes, or 8 on CPU
// devices (SIMD across a brick of points) and 1 elsewhere (a work item per point).
int density_lanes(const ComputeContext& ctx, const DescriptorOptions& options) {
  if (options.density_lanes != 0) return options.density_lanes;
  return ctx.device.info.type == "cpu" ? 8 : 1;
}

cl::Kernel make_kernel(const ComputeContext& ctx, const std::string& name, int stack_size,
                       const DescriptorOptions& options, const std::string& variant = "") {
  // Each descriptor kernel is compiled with the shared geometry in front of it.
  const std::string source = kernel_source("geometry") + "\n" + kernel_source(name);
  const std::string flags = "-cl-std=CL1.2 -D STACK_SIZE=" + std::to_string(stack_size) + variant;
  return cl::Kernel(build_program(ctx, name, source, flags, options.program_cache).program, name.c_str());
}

}  // namespace

namespace {

// The points the passes evaluate, in grid units (the mesh is transformed the same way):
// the grid's points, or an explicit list of coordinates.
struct EvalPoints {
  GridSpec grid;                          // origin 0, spacing 1; for a list: dims (count, 1, 1)
  const std::vector<float>* x = nullptr;  // explicit coordinates (all three or none)
  const std::vector<float>* y = nullptr;
  const std::vector<float>* z = nullptr;
  bool explicit_points() const { return x != nullptr; }
  std::size_t count() const { return grid.count(); }
};

void check_inputs(const Mesh& mesh, const DescriptorParams& params, const DescriptorOptions& options) {
  if (mesh.empty()) throw Error("cannot compute descriptors of an empty mesh");
  if (options.chunk_points == 0) throw Error("descriptor chunk size must be positive");
  if (!(params.tolerance > 0 && params.tolerance < 1)) throw Error("descriptor tolerance must be in (0, 1)");
  if (params.kind == DescriptorKind::skeletal_density && !(params.sigma > 0))
    throw Error("descriptor sigma must be positive");
}

// Pass 3: the skeletal density s and its error bound at every point, from |xi| (the
// density BVH's nodes and triangles already on the device), into out.
void skeletal_density_pass(const ComputeContext& ctx, const EvalPoints& points, const DescriptorParams& params,
                           const DescriptorOptions& options, const std::vector<float>& distance,
                           const cl::Buffer& density_nodes, const cl::Buffer& density_triangles,
                           std::size_t density_triangle_count, int stack_size, const std::string& explicit_flag,
                           DescriptorFields& out) {
  const GridSpec& grid = points.grid;
  const std::size_t count = points.count();
  // Points in packets of `lanes` neighbours (kernels/skeletal_density.cl): bricks of the
  // grid, or the list's points in their order; |xi| (and the coordinates of a list)
  // gathered into packet order, s and its bound scattered back.
  const int lanes = density_lanes(ctx, options);
  std::vector<long long> order;
  if (points.explicit_points()) {
    order.assign((count + lanes - 1) / lanes * lanes, -1);
    for (std::size_t i = 0; i < count; ++i) order[i] = static_cast<long long>(i);
  } else {
    order = brick_point_order(grid, lanes);
  }
  auto gather = [&](const std::vector<float>& from, float padding) {
    std::vector<float> to(order.size(), padding);
    for (std::size_t i = 0; i < order.size(); ++i)
      if (order[i] >= 0) to[i] = from[static_cast<std::size_t>(order[i])];
    return to;
  };
  std::vector<float> ordered_distance = gather(distance, 1.0f), ordered_density(order.size()),
                     ordered_bound(order.size());
  std::vector<std::vector<float>> ordered_coordinates;
  if (points.explicit_points())
    for (const std::vector<float>* c : {points.x, points.y, points.z}) ordered_coordinates.push_back(gather(*c, 0.0f));
  static_assert(sizeof(long long) == sizeof(cl_long), "point ids are OpenCL longs");
  cl::Buffer id_buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_long) * order.size(),
                       const_cast<long long*>(order.data()));
  const std::size_t packet_chunk = (std::min(options.chunk_points, order.size()) + lanes - 1) / lanes * lanes;
  auto chunk_buffer = [&](cl_mem_flags flags) { return cl::Buffer(ctx.context, flags, sizeof(float) * packet_chunk); };
  std::vector<ChunkIo> inputs = {{chunk_buffer(CL_MEM_READ_ONLY), &ordered_distance}};
  for (std::vector<float>& c : ordered_coordinates) inputs.push_back({chunk_buffer(CL_MEM_READ_ONLY), &c});
  cl::Buffer out_density = chunk_buffer(CL_MEM_WRITE_ONLY), out_bound = chunk_buffer(CL_MEM_WRITE_ONLY);
  cl::Kernel density_kernel =
      make_kernel(ctx, "skeletal_density", stack_size, options,
                  " -D LANES=" + std::to_string(lanes) +
                      (options.brute_force_density ? " -D BRUTE_FORCE -D MAX_SPLIT_DEPTH=40" : "") + explicit_flag);
  density_kernel.setArg(6, density_nodes);
  density_kernel.setArg(7, density_triangles);
  density_kernel.setArg(8, inputs[0].buffer);
  density_kernel.setArg(9, static_cast<float>(options.min_distance_fraction * grid.spacing));
  density_kernel.setArg(10, static_cast<float>(params.sigma));
  density_kernel.setArg(11, static_cast<float>(params.tolerance));
  density_kernel.setArg(12, static_cast<cl_int>(density_triangle_count));
  density_kernel.setArg(13, out_density);
  density_kernel.setArg(14, out_bound);
  density_kernel.setArg(15, id_buffer);
  for (std::size_t a = 1; a < inputs.size(); ++a) density_kernel.setArg(16 + cl_uint(a - 1), inputs[a].buffer);
  run_pass(ctx, grid, options, density_kernel, inputs, {{out_density, &ordered_density}, {out_bound, &ordered_bound}},
           "skeletal density", order.size(), packet_chunk, static_cast<std::size_t>(lanes));
  out.skeletal_density.resize(count);
  out.density_bound.resize(count);
  for (std::size_t i = 0; i < order.size(); ++i) {
    if (order[i] < 0) continue;
    out.skeletal_density[static_cast<std::size_t>(order[i])] = ordered_density[i];
    out.density_bound[static_cast<std::size_t>(order[i])] = ordered_bound[i];
  }
  out.density_lanes = lanes;
}

// The three passes (distance, winding number, skeletal density) at `points`, for a mesh
// already in grid units. Fills out's winding, bounds and skeletal density and returns
// the unsigned distances (grid units; empty when not needed).
std::vector<float> run_passes(const ComputeContext& ctx, const Mesh& mesh, const EvalPoints& points,
                              const DescriptorParams& params, const DescriptorOptions& options,
                              bool compute_signed_distance, DescriptorFields& out) {
  const GridSpec& grid = points.grid;
  const bool skeletal = params.kind == DescriptorKind::skeletal_density;
  const bool need_distance = skeletal || compute_signed_distance;
  // Sign propagation needs the distance too (cheap next to the winding kernel); it needs
  // a grid. (Component labels are 32-bit: larger grids keep the full pass.)
  const bool propagate = !points.explicit_points() && options.winding_sign_propagation &&
                         grid.count() <= static_cast<std::size_t>(INT32_MAX) && mesh_is_closed(mesh);
  const bool compute_distance = need_distance || propagate;
  const std::string explicit_flag = points.explicit_points() ? " -D EXPLICIT_POINTS" : "";

  // Distance and winding number run on the mesh as given; the skeletal density on
  // the refined mesh, whose small leaves it integrates without per-point splitting.
  auto t = std::chrono::steady_clock::now();
  const TriangleBvh bvh = build_triangle_bvh(mesh, options.bvh_leaf_size);
  TriangleBvh refined_bvh;
  if (skeletal && options.refine_fraction > 0 && !options.brute_force_density) {
    const Mesh refined = refine_triangles(mesh, options.refine_fraction * grid.spacing);
    out.refine_seconds = seconds_since(t);
    refined_bvh = build_triangle_bvh(refined, options.bvh_leaf_size);
  }
  const TriangleBvh& density_bvh = refined_bvh.nodes.empty() ? bvh : refined_bvh;
  out.bvh_seconds = seconds_since(t) - out.refine_seconds;
  out.refined_triangles = density_bvh.triangles.size() / 3;
  // A traversal holds at most depth + 1 nodes on its stack.
  const int stack_size = std::max(bvh.depth, density_bvh.depth) + 8;

  const std::size_t count = points.count();
  std::vector<float> distance(compute_distance ? count : 0);
  out.winding.resize(count);
  out.winding_bound.resize(count);
  const std::size_t chunk = std::min(options.chunk_points, count);
  cl::Buffer nodes(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(BvhNode) * bvh.nodes.size(),
                   const_cast<BvhNode*>(bvh.nodes.data()));
  cl::Buffer triangles(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_float4) * bvh.triangles.size(),
                       const_cast<cl_float4*>(bvh.triangles.data()));
  cl::Buffer density_nodes = nodes, density_triangles = triangles;
  if (&density_bvh != &bvh) {
    density_nodes =
        cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(BvhNode) * density_bvh.nodes.size(),
                   const_cast<BvhNode*>(density_bvh.nodes.data()));
    density_triangles = cl::Buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                                   sizeof(cl_float4) * density_bvh.triangles.size(),
                                   const_cast<cl_float4*>(density_bvh.triangles.data()));
  }
  cl::Buffer chunk_a(ctx.context, CL_MEM_READ_WRITE, sizeof(float) * chunk);
  cl::Buffer chunk_b(ctx.context, CL_MEM_READ_WRITE, sizeof(float) * chunk);
  // The explicit points' coordinates, chunk by chunk (inputs of every pass).
  std::vector<ChunkIo> coordinates;
  if (points.explicit_points())
    for (const std::vector<float>* c : {points.x, points.y, points.z})
      coordinates.push_back(
          {cl::Buffer(ctx.context, CL_MEM_READ_ONLY, sizeof(float) * chunk), const_cast<std::vector<float>*>(c)});
  auto bind_coordinates = [&](cl::Kernel& kernel, cl_uint first_arg, const std::vector<ChunkIo>& buffers) {
    for (std::size_t a = 0; a < buffers.size(); ++a) kernel.setArg(first_arg + cl_uint(a), buffers[a].buffer);
  };

  // 1. Unsigned distance |xi| (not for the indicator, which needs w alone).
  t = std::chrono::steady_clock::now();
  if (compute_distance) {
    cl::Kernel distance_kernel = make_kernel(ctx, "unsigned_distance", stack_size, options, explicit_flag);
    distance_kernel.setArg(6, nodes);
    distance_kernel.setArg(7, triangles);
    distance_kernel.setArg(8, chunk_a);
    bind_coordinates(distance_kernel, 9, coordinates);
    run_pass(ctx, grid, options, distance_kernel, coordinates, {{chunk_a, &distance}}, "distance", count, chunk);
    out.distance_seconds = seconds_since(t);
  }
  t = std::chrono::steady_clock::now();

  // 2. Winding number w and its error bound: on a closed mesh at one seed per
  // component of the "surface cannot cross" grid graph, copied to the component;
  // otherwise at every point.
  cl::Kernel winding_kernel =
      make_kernel(ctx, "winding_number", stack_size, options, (propagate ? " -D POINT_LIST" : "") + explicit_flag);
  winding_kernel.setArg(6, nodes);
  winding_kernel.setArg(7, triangles);
  winding_kernel.setArg(8, static_cast<float>(params.tolerance));
  winding_kernel.setArg(9, chunk_a);
  winding_kernel.setArg(10, chunk_b);
  if (propagate) {
    const WindingComponents components = winding_components(grid, distance, distance_rounding_slack(grid, mesh));
    const std::size_t seeds = components.seeds.size();
    std::vector<cl_long> ids(components.seeds.begin(), components.seeds.end());
    cl::Buffer id_buffer(ctx.context, CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(cl_long) * seeds, ids.data());
    winding_kernel.setArg(11, id_buffer);
    std::vector<float> seed_winding(seeds), seed_bound(seeds);
    run_pass(ctx, grid, options, winding_kernel, {}, {{chunk_a, &seed_winding}, {chunk_b, &seed_bound}},
             "winding number", seeds, chunk);
    propagate_winding(components, seed_winding, seed_bound, out.winding, out.winding_bound);
    out.winding_method = "sign propagation";
    out.winding_kernel_points = seeds;
  } else {
    bind_coordinates(winding_kernel, 11, coordinates);
    run_pass(ctx, grid, options, winding_kernel, coordinates, {{chunk_a, &out.winding}, {chunk_b, &out.winding_bound}},
             "winding number", count, chunk);
    out.winding_kernel_points = count;
  }
  out.winding_seconds = seconds_since(t);
  t = std::chrono::steady_clock::now();

  // 3. Skeletal density s and its error bound, from |xi|.
  if (skeletal) {
    skeletal_density_pass(ctx, points, params, options, distance, density_nodes, density_triangles,
                          density_bvh.triangles.size() / 3, stack_size, explicit_flag, out);
    out.density_seconds = seconds_since(t);
  }
  return distance;
}

// The mesh in the grid units of `frame` (origin and spacing): (v - origin) / spacing, in
// double. Float round-off is then relative to the grid whatever the scene's scale, and a
// vertex on a grid plane lands exactly on it. Only |xi| has a length unit.
Mesh mesh_in_grid_units(const Mesh& scene_mesh, const Eigen::Vector3d& origin, double spacing) {
  Mesh mesh = scene_mesh;
  for (Eigen::Vector3d& v : mesh.vertices) v = (v - origin) / spacing;
  return mesh;
}

// xi from |xi| (grid units) and w: negative inside (w >= 1/2), scene units.
std::vector<float> signed_distance(const std::vector<float>& distance, const std::vector<float>& winding,
                                   double spacing) {
  std::vector<float> xi(distance.size());
  for (std::size_t i = 0; i < xi.size(); ++i) {
    const float d = static_cast<float>(distance[i] * spacing);
    xi[i] = winding[i] >= 0.5f ? -d : d;
  }
  return xi;
}

Error device_failure(const ComputeContext& ctx, const cl::Error& e) {
  return Error("descriptor computation failed on device " + ctx.device.info.name + ": " + e.what() + " (error " +
               std::to_string(e.err()) + ")");
}

}  // namespace

DescriptorFields compute_descriptors(const ComputeContext& ctx, const Mesh& scene_mesh, const GridSpec& scene_grid,
                                     const DescriptorParams& params, const DescriptorOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_inputs(scene_mesh, params, options);
  if (scene_grid.count() == 0) throw Error("cannot compute descriptors on an empty grid");
  if (!(scene_grid.spacing > 0) || !std::isfinite(scene_grid.spacing) || !scene_grid.origin.allFinite())
    throw Error("cannot compute descriptors on a grid with a non-finite origin or a non-positive spacing");
  // Everything below works in grid units: grid points at integer coordinates.
  const Mesh mesh = mesh_in_grid_units(scene_mesh, scene_grid.origin, scene_grid.spacing);
  EvalPoints points;
  points.grid = scene_grid;
  points.grid.origin = Eigen::Vector3d::Zero();
  points.grid.spacing = 1.0;

  DescriptorFields out;
  out.grid = scene_grid;
  out.params = params;
  const bool skeletal = params.kind == DescriptorKind::skeletal_density;
  try {
    const std::vector<float> distance =
        run_passes(ctx, mesh, points, params, options, options.indicator_signed_distance, out);
    if (skeletal || options.indicator_signed_distance)
      out.signed_distance = signed_distance(distance, out.winding, scene_grid.spacing);
  } catch (const cl::Error& e) {
    throw device_failure(ctx, e);
  }
  out.seconds = seconds_since(start);
  return out;
}

DescriptorFields descriptors_at_points(const ComputeContext& ctx, const Mesh& scene_mesh,
                                       const std::vector<Eigen::Vector3d>& scene_points, const Eigen::Vector3d& origin,
                                       double spacing, const DescriptorParams& params,
                                       const DescriptorOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  check_inputs(scene_mesh, params, options);
  if (!(spacing > 0) || !std::isfinite(spacing) || !origin.allFinite())
    throw Error("descriptors at points: the unit frame needs a finite origin and a positive spacing");
  DescriptorFields out;
  out.params = params;
  out.grid.origin = Eigen::Vector3d::Zero();
  out.grid.spacing = spacing;
  out.grid.dims = Eigen::Vector3i(static_cast<int>(scene_points.size()), 1, 1);
  if (scene_points.empty()) return out;
  const Mesh mesh = mesh_in_grid_units(scene_mesh, origin, spacing);
  std::vector<float> x(scene_points.size()), y(x.size()), z(x.size());
  for (std::size_t i = 0; i < scene_points.size(); ++i) {
    if (!scene_points[i].allFinite())
      throw Error("descriptors at points: point " + std::to_string(i) + " is not finite");
    const Eigen::Vector3d u = (scene_points[i] - origin) / spacing;
    x[i] = static_cast<float>(u.x());
    y[i] = static_cast<float>(u.y());
    z[i] = static_cast<float>(u.z());
  }
  EvalPoints points;
  points.grid.dims = out.grid.dims;
  points.x = &x;
  points.y = &y;
  points.z = &z;
  const bool skeletal = params.kind == DescriptorKind::skeletal_density;
  try {
    const std::vector<float> distance =
        run_passes(ctx, mesh, points, params, options, options.indicator_signed_distance, out);
    if (skeletal || options.indicator_signed_distance)
      out.signed_distance = signed_distance(distance, out.winding, spacing);
  } catch (const cl::Error& e) {
    throw device_failure(ctx, e);
  }
  out.seconds = seconds_since(start);
  return out;
}

std::vector<float> affinity_imaginary(const DescriptorFields& fields) {
  std::vector<float> rho(fields.winding.size());
  const bool skeletal = fields.params.kind == DescriptorKind::skeletal_density;
  for (std::size_t i = 0; i < rho.size(); ++i) {
    const bool inside = fields.winding[i] >= 0.5f;
    if (!skeletal) {
      rho[i] = inside ? 1.0f : 0.0f;
    } else {
      const double lambda = inside ? fields.params.lambda_in : fields.params.lambda_out;
      rho[i] = static_cast<float>(lambda * fields.skeletal_density[i]);
    }
  }
  return rho;
}

}  // namespace snapfit
