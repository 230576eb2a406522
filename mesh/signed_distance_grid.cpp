#include "mesh/signed_distance_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mesh/mesh_distance.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

// Trilinear interpolation of the 8 corner values c[i + 2 j + 4 k] at fraction f of a
// cell of size h, and the interpolant's gradient.
double trilinear(const float c[8], const Eigen::Vector3d& f, double h, Eigen::Vector3d* gradient) {
  const double x = f.x(), y = f.y(), z = f.z();
  const double c00 = c[0] + (c[1] - c[0]) * x, c10 = c[2] + (c[3] - c[2]) * x;
  const double c01 = c[4] + (c[5] - c[4]) * x, c11 = c[6] + (c[7] - c[6]) * x;
  const double c0 = c00 + (c10 - c00) * y, c1 = c01 + (c11 - c01) * y;
  if (gradient) {
    const double dx0 = (c[1] - c[0]) * (1 - y) + (c[3] - c[2]) * y;
    const double dx1 = (c[5] - c[4]) * (1 - y) + (c[7] - c[6]) * y;
    (*gradient) << (dx0 * (1 - z) + dx1 * z) / h, ((c10 - c00) * (1 - z) + (c11 - c01) * z) / h, (c1 - c0) / h;
  }
  return c0 + (c1 - c0) * z;
}

}  // namespace

SignedDistanceGrid build_signed_distance_grid(const Mesh& mesh, double spacing, double band, double margin,
                                              int refine, const Eigen::AlignedBox3d* keep) {
  if (mesh.empty()) throw Error("signed distance grid: the mesh has no triangles");
  if (!(std::isfinite(spacing) && spacing > 0)) throw Error("signed distance grid: spacing must be > 0");
  if (!(std::isfinite(band) && band > 0)) throw Error("signed distance grid: band must be > 0");
  if (!(std::isfinite(margin) && margin > 0)) throw Error("signed distance grid: margin must be > 0");
  if (refine < 1 || refine > 16) throw Error("signed distance grid: refine must be 1 to 16");
  const MeshDistanceIndex index(mesh);
  SignedDistanceGrid g;
  g.refine = refine;
  g.coarse = spacing * refine;
  g.band = band;
  g.part_min = index.box_min();
  g.part_max = index.box_max();
  const double grow = std::max(margin, band + g.coarse);
  g.origin = g.part_min - Eigen::Vector3d::Constant(grow);
  const Eigen::Vector3d size = g.part_max - g.part_min + Eigen::Vector3d::Constant(2 * grow);
  for (int a = 0; a < 3; ++a) g.dims[a] = static_cast<int>(std::ceil(size[a] / g.coarse)) + 1;
  if (keep) {  // the nodes of the whole grid that cover `keep`: the same values where both have them
    for (int a = 0; a < 3; ++a) {
      const int first = std::max(0, static_cast<int>(std::floor((keep->min()[a] - g.origin[a]) / g.coarse)));
      const int last = std::min(g.dims[a] - 1, static_cast<int>(std::ceil((keep->max()[a] - g.origin[a]) / g.coarse)));
      if (last - first < 1) throw Error("signed distance grid: the box kept does not overlap the part's grid");
      g.origin[a] += first * g.coarse;
      g.dims[a] = last - first + 1;
    }
  }
  const std::size_t nx = g.dims.x(), ny = g.dims.y(), nz = g.dims.z();
  if (nx * ny * nz > 200000000) throw Error("signed distance grid: too many coarse nodes; use a larger spacing");

  g.coarse_values.resize(nx * ny * nz);
  tbb::parallel_for(std::size_t(0), nz, [&](std::size_t k) {
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        g.coarse_values[i + nx * (j + ny * k)] = static_cast<float>(
            index.signed_distance(g.origin + g.coarse * Eigen::Vector3d(double(i), double(j), double(k))));
  });

  // Cells that may hold a point within `band` of the surface get a fine brick.
  const double reach = band + g.coarse * std::sqrt(3.0);
  const std::size_t cx = nx - 1, cy = ny - 1, cz = nz - 1;
  g.brick_of_cell.assign(cx * cy * cz, kCoarseOutside);
  std::vector<std::size_t> refined;
  for (std::size_t k = 0; k < cz; ++k)
    for (std::size_t j = 0; j < cy; ++j)
      for (std::size_t i = 0; i < cx; ++i) {
        double nearest = INFINITY;
        for (int c = 0; c < 8; ++c)
          nearest = std::min(nearest, std::abs(double(
                                          g.coarse_values[(i + (c & 1)) + nx * ((j + (c >> 1 & 1)) + ny * (k + (c >> 2)))])));
        if (nearest <= reach) {
          g.brick_of_cell[i + cx * (j + cy * k)] = static_cast<std::int32_t>(refined.size());
          refined.push_back(i + cx * (j + cy * k));
        } else if (g.coarse_values[i + nx * (j + ny * k)] < 0) {  // |d| > band over the cell: one sign
          g.brick_of_cell[i + cx * (j + cy * k)] = kCoarseInside;
        }
      }
  const std::size_t per = g.brick_nodes(), side = refine + 1;
  g.brick_values.resize(refined.size() * per);
  const double h = g.fine_spacing();
  g.brick_step = h / kBrickStepsPerSpacing;
  tbb::parallel_for(std::size_t(0), refined.size(), [&](std::size_t b) {
    const std::size_t cell = refined[b];
    const Eigen::Vector3d corner =
        g.origin + g.coarse * Eigen::Vector3d(double(cell % cx), double(cell / cx % cy), double(cell / (cx * cy)));
    for (std::size_t n = 0; n < per; ++n) {
      const double d = index.signed_distance(
          corner + h * Eigen::Vector3d(double(n % side), double(n / side % side), double(n / (side * side))));
      const double steps = std::clamp(std::round(d / g.brick_step), -32767.0, 32767.0);
      g.brick_values[b * per + n] = static_cast<std::int16_t>(steps);
    }
  });
  return g;
}

namespace {

// sample_signed_distance, also giving the spacing of the cell interpolated (0 outside the grid).
double sample(const SignedDistanceGrid& g, const Eigen::Vector3d& p, Eigen::Vector3d* gradient, double& cell_spacing) {
  const Eigen::Vector3d local = (p - g.origin) / g.coarse;
  Eigen::Vector3i cell;
  bool inside_grid = true;
  for (int a = 0; a < 3; ++a) {
    cell[a] = static_cast<int>(std::floor(local[a]));
    inside_grid = inside_grid && cell[a] >= 0 && cell[a] < g.dims[a] - 1;
  }
  if (!inside_grid) {  // farther from the part than the grid's margin: the box distance bounds it
    const Eigen::Vector3d away = (p - p.cwiseMax(g.part_min).cwiseMin(g.part_max));
    const double d = away.norm();
    if (gradient) *gradient = d > 0 ? Eigen::Vector3d(away / d) : Eigen::Vector3d::Zero();
    cell_spacing = 0;
    return d;
  }
  const std::size_t nx = g.dims.x(), ny = g.dims.y(), cx = nx - 1, cy = ny - 1;
  const std::int32_t brick = g.brick_of_cell[cell.x() + cx * (cell.y() + cy * std::size_t(cell.z()))];
  Eigen::Vector3d f = local - cell.cast<double>();
  float c[8];
  if (brick < 0) {
    for (int n = 0; n < 8; ++n)
      c[n] = g.coarse_values[(cell.x() + (n & 1)) + nx * ((cell.y() + (n >> 1 & 1)) + ny * (cell.z() + (n >> 2)))];
    cell_spacing = g.coarse;
    return trilinear(c, f, g.coarse, gradient);
  }
  const int r = g.refine;
  const std::size_t side = r + 1;
  Eigen::Vector3i sub;
  for (int a = 0; a < 3; ++a) {
    const double s = f[a] * r;
    sub[a] = std::clamp(static_cast<int>(std::floor(s)), 0, r - 1);
    f[a] = s - sub[a];
  }
  const std::size_t first = std::size_t(brick) * g.brick_nodes();
  for (int n = 0; n < 8; ++n)
    c[n] = g.brick_value(first + (sub.x() + (n & 1)) + side * ((sub.y() + (n >> 1 & 1)) + side * (sub.z() + (n >> 2))));
  cell_spacing = g.fine_spacing();
  return trilinear(c, f, g.fine_spacing(), gradient);
}

}  // namespace

double sample_signed_distance(const SignedDistanceGrid& g, const Eigen::Vector3d& p, Eigen::Vector3d* gradient) {
  double cell_spacing = 0;
  return sample(g, p, gradient, cell_spacing);
}

double signed_distance_lower_bound(const SignedDistanceGrid& g, const Eigen::Vector3d& p) {
  double cell_spacing = 0;
  const double d = sample(g, p, nullptr, cell_spacing);
  return d - (0.5 * std::sqrt(3.0) + 1e-4) * cell_spacing - 1e-6 * std::abs(d) - g.brick_step;
}

}  // namespace snapfit
