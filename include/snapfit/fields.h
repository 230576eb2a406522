#pragma once
// A scene part's descriptor fields on its grid (Behandish & Ilies 2016 sec. 2.3 and 3.1;
// docs/design.md "Shape descriptors"), from the field cache when a matching entry exists,
// else computed on the device and cached:
//   w    generalized winding number (1 inside, 0 outside; robust on open meshes)
//   xi   signed distance to the boundary, negative inside (w >= 1/2)
//   s    skeletal density: s > 0 inside, s < 0 outside
// with a per-point bound on the quadrature error of w and of s. The indicator descriptor
// (collision response only) computes w alone.
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "snapfit/grid.h"
#include "snapfit/scene.h"

namespace snapfit {

struct DescriptorFields {
  GridSpec grid;
  DescriptorParams params;
  std::vector<float> winding;           // w
  std::vector<float> winding_bound;     // bound on |w error|
  std::vector<float> signed_distance;   // xi, scene units (empty for the indicator kind)
  std::vector<float> skeletal_density;  // s (empty for the indicator kind)
  std::vector<float> density_bound;     // bound on |s error| (empty for the indicator kind)
  // How w was computed: "sign propagation" (closed mesh: the kernel at one seed per
  // component) or "full" (the kernel at every point).
  std::string winding_method = "full";
  int density_lanes = 0;                       // points per density work item (0: not computed here)
  std::size_t winding_kernel_points = 0;       // points where the winding kernel ran (not known from the cache)
  double seconds = 0;                          // wall time of the computation
  double refine_seconds = 0, bvh_seconds = 0;  // host work
  double distance_seconds = 0, winding_seconds = 0, density_seconds = 0;  // kernels (incl. build)
  std::size_t refined_triangles = 0;
};

struct PartFieldsResult {
  DescriptorFields fields;
  bool from_cache = false;
};

// The affinity rho = i * lambda * s (docs/design.md): its imaginary part lambda * s, with
// lambda = lambda_in where w >= 1/2 and lambda_out elsewhere. For the indicator kind,
// the indicator itself (1 inside, 0 outside), real-valued.
std::vector<float> affinity_imaginary(const DescriptorFields& fields);

// A segment of a mesh's cut by an axis plane, in the plane's (u, v) coordinates.
struct OutlineSegment {
  Eigen::Vector2d a, b;  // (u, v) in the mesh's units
};

struct PartFieldsRequest {
  int part = 2;        // 1 (fixed) or 2 (moving)
  std::string device;  // as AssemblyOptions::device
  bool use_cache = true;
  bool progress = false;                         // progress bars on stderr while the fields are computed
  std::function<void(const std::string&)> note;  // cache messages; default: stderr
  // An axis plane ('x', 'y' or 'z', coordinate in the part's frame): checked against the
  // part's grid before any device work, and the part's outline there returned.
  std::optional<std::pair<char, double>> slice;
};

struct ScenePartFields {
  PartFieldsResult result;              // the fields and whether they came from the cache
  GridSpec grid;                        // the part's grid, in its own frame
  std::size_t triangles = 0;            // of the part's mesh
  std::string device;                   // the device's name
  int slice_index = 0;                  // with a slice: the grid plane nearest it along its axis
  double slice_plane = 0;               // that plane's coordinate
  std::vector<OutlineSegment> outline;  // the part's mesh cut by that plane
};

// Builds the scene's parts and the part's grid (at the spacing both parts share), then
// its fields. Throws snapfit::Error for a part other than 1 or 2, a slice outside the
// grid, a mesh that cannot be made, or a device failure.
ScenePartFields scene_part_fields(const Scene& scene, const PartFieldsRequest& request);

// Where a part's fields came from (cache or computed), how long they took, and their
// error bounds, as `snapfit fields` and `snapfit run` print them.
std::string fields_summary_text(const PartFieldsResult& result);

}  // namespace snapfit
