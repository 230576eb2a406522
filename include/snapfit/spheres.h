#pragma once
// A part's spherical decomposition (Behandish & Ilies 2015 Algorithm 1, docs/spheres.md):
// balls centred at the grid nodes inside the solid, radius the distance to the boundary,
// chosen greedily in descending skeletal density, expanded by the Hausdorff bound epsilon
// and reduced to those not engulfed by another, with the union's error against the solid.
//
//   snapfit::PartSpheresRequest request;
//   request.part = 1;
//   request.tolerances = {0.5};
//   snapfit::PartSpheres spheres = snapfit::decompose_part_spheres(scene, request);
#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "snapfit/scene.h"

namespace snapfit {

struct Ball {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0;
};

// Which field orders the greedy selection.
enum class BallOrder {
  skeletal_density,  // Behandish & Ilies 2015: the skeletal density, ridges on the medial structure
  distance,          // largest ball first (an inner sphere packing)
};

struct SphereDecomposition {
  std::vector<Ball> balls;        // A3
  std::size_t sampled_balls = 0;  // n1 = n2 = |A1|
  std::size_t grid_nodes = 0;     // m = |G|
  std::size_t inside_nodes = 0;   // |X| = |G n S|
  double spacing = 0;             // of G
  double epsilon = 0;             // Hausdorff bound (Proposition 3): half a cell's diagonal
  double field_seconds = 0;       // distance, winding and skeletal density on G (OpenCL)
  double seconds = 0;             // everything, fields included
};

// How far a union of balls is from the solid: the volume of the symmetric difference,
// estimated by uniform sampling of a box around both with a 95 % Wilson interval, and a
// sampled Hausdorff distance (a lower estimate, to set against the proven bound epsilon).
struct BallUnionError {
  double volume_error = 0;                             // |S xor U|, scene units^3
  double volume_error_low = 0, volume_error_high = 0;  // 95 % Wilson interval
  double solid_volume = 0;                             // |S| from the mesh (divergence theorem)
  double sample_box_volume = 0;
  double hausdorff_sampled = 0;  // lower estimate of d_H(S, U)
  std::size_t samples = 0, mismatched = 0;
  double seconds = 0;
};

struct PartSpheresRequest {
  int part = 1;  // 1 (fixed) or 2 (moving)
  // Hausdorff bounds epsilon in scene units, one decomposition each; empty: the scene's
  // grid spacing. The decomposition grid has spacing 2 epsilon / sqrt(3).
  std::vector<double> tolerances;
  double protrusion = 0.25;  // mu of Behandish & Ilies 2015 (A.1), in [0, 1]
  BallOrder order = BallOrder::skeletal_density;
  std::size_t samples = 200000;  // uniform samples for the volume and Hausdorff error
  std::string device;            // as AssemblyOptions::device
  bool progress = false;         // progress bars on stderr while fields are computed
};

struct SpheresAtTolerance {
  double tolerance = 0;
  SphereDecomposition decomposition;
  BallUnionError error;
};

// Called with each tolerance's result as soon as it is measured (to report as they come).
using SpheresCallback = std::function<void(const SpheresAtTolerance&)>;

struct PartSpheres {
  std::vector<SpheresAtTolerance> levels;  // in the request's order
};

// Builds the scene's part (in its own frame) and decomposes it at each tolerance on the
// device. Throws snapfit::Error for a part other than 1 or 2, a tolerance that is not
// positive and finite or gives a grid over 2^31 points (before any device work), no
// samples, and device failures.
PartSpheres decompose_part_spheres(const Scene& scene, const PartSpheresRequest& request,
                                   const SpheresCallback& on_level = {});

}  // namespace snapfit
