#include "scheduler/haptics/contact_block.h"

#include "scheduler/haptics/block_distances.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace snapfit {

PointMap point_map(const Eigen::Matrix3d& to_grid, const Eigen::Matrix3d& to_arm, const Eigen::Matrix3d& to_world,
                   double sign, const SignedDistanceGrid& grid) {
  PointMap m;
  m.to_grid = to_grid, m.to_arm = to_arm, m.to_world = to_world, m.sign = sign;
  const double per_spacing = 1 / grid.fine_spacing();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      m.to_fine[3 * r + c] = per_spacing * to_grid(r, c);
      m.to_arm_f[3 * r + c] = float(to_arm(r, c));
      m.to_dphi_dt[3 * r + c] = float(sign * per_spacing * grid.brick_step * to_world(r, c));
    }
  return m;
}

namespace {

// Adds the term of a point at offset d with distance phi (< -skin) and the grid's
// gradient `gradient` (per scene unit, the grid's frame).
void add_term(const PointMap& map, const Eigen::Vector3d& centre_arm, const Eigen::Vector3d& d, double phi,
              const Eigen::Vector3d& gradient, double area, const ContactConstants& k, ContactSum& sum) {
  const Eigen::Vector3d g = map.sign * (map.to_world * gradient);
  const Eigen::Vector3d turn = (centre_arm + map.to_arm * d).cross(g) * k.metres_per_unit;
  const double j[6] = {g.x(), g.y(), g.z(), turn.x(), turn.y(), turn.z()};
  sum.add(k.k_area * area, k.metres_per_unit * (phi + k.skin), j, phi);
}

// Where a point (the grid's frame) lies on the fine level: the node at its cell's lowest
// corner (null off the fine level) and its fraction in the cell.
struct FineCell {
  const std::int16_t* node = nullptr;
  double fraction[3] = {0, 0, 0};
};

FineCell locate(const FineDistanceView& view, const SignedDistanceGrid& grid, const Eigen::Vector3d& p) {
  FineCell c;
  const Eigen::Vector3d local = (p - grid.origin) * (1 / grid.fine_spacing());
  if (!(local.array().abs() < 1e9).all()) return c;  // far off the grid, or not finite
  int cell[3];
  for (int a = 0; a < 3; ++a) cell[a] = floor_to_int(local[a]), c.fraction[a] = local[a] - cell[a];
  c.node = view.node(cell[0], cell[1], cell[2]);
  return c;
}

// Whether no point within `radius` of a centre whose exact distance is at least `lower`
// can be deeper than the skin: a point in a fine cell is interpolated within sqrt(3)/2
// fine spacings of its exact distance; one in a coarse cell (beyond the band) or off the
// grid keeps its sign.
bool clear(double lower, double radius, double skin, double fine_spacing) {
  const double nearest = lower - radius;
  return nearest > 0 && nearest - (0.5 * std::sqrt(3.0) + 1e-4) * fine_spacing >= -skin;
}

// The lower bound of the exact distance at a point located at `c` (p itself for the
// double path off the fine level): as signed_distance_lower_bound.
double lower_bound(const FineDistanceView& view, const SignedDistanceGrid& grid, const FineCell& c,
                   const Eigen::Vector3d& p) {
  if (!c.node) return signed_distance_lower_bound(grid, p);
  const double d = view.value(c.node, c.fraction[0], c.fraction[1], c.fraction[2]);
  return d - (0.5 * std::sqrt(3.0) + 1e-4) * grid.fine_spacing() - 1e-6 * std::abs(d) - grid.brick_step;
}

void add_block_contact(const ContactBlocks& points, const ShellChunk& block, const PointMap& map,
                       const Eigen::Vector3d& centre_grid, const Eigen::Vector3d& centre_arm,
                       const SignedDistanceGrid& grid, const FineDistanceView& shared_view, const ContactConstants& k,
                       ContactSum& sum) {
  const std::size_t n = block.end - block.begin;
  const float *x = points.x.data() + block.begin, *y = points.y.data() + block.begin,
              *z = points.z.data() + block.begin, *area = points.area.data() + block.begin;
  const auto offset = [&](std::size_t i) { return Eigen::Vector3d(x[i], y[i], z[i]); };
  // The double path, for a point off the fine level.
  const auto add_exactly = [&](std::size_t i) {
    Eigen::Vector3d gradient;
    const double phi = sample_signed_distance(grid, centre_grid + map.to_grid * offset(i), &gradient);
    if (phi < -k.skin) add_term(map, centre_arm, offset(i), phi, gradient, area[i], k, sum);
  };

  BlockDistances cells;
  if (!block_distances(points, block, map.to_fine, centre_grid, grid, shared_view, cells)) {
    for (std::size_t i = 0; i < n; ++i) add_exactly(i);
    return;
  }
  const std::int16_t* const* nodes = cells.node;
  const double *fx = cells.fx, *fy = cells.fy, *fz = cells.fz;
  const FineDistanceView view = shared_view;  // a local copy: its fields stay in registers

  // Pass 3: each point's distance; those deeper than the skin are kept.
  std::uint8_t deep[kMaxBlockPoints];
  double deep_phi[kMaxBlockPoints];
  std::size_t deeper = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!nodes[i]) {
      if (!cells.outside[i]) add_exactly(i);
      continue;
    }
    const double phi = cells.phi[i];
    if (phi < -k.skin) deep[deeper] = std::uint8_t(i), deep_phi[deeper++] = phi;
  }

  if (deeper == 0) return;

  // The stiffness's lower triangle, row by row (ContactSum's order).
  static constexpr int kRow[21] = {0, 1, 1, 2, 2, 2, 3, 3, 3, 3, 4, 4, 4, 4, 4, 5, 5, 5, 5, 5, 5};
  static constexpr int kColumn[21] = {0, 0, 1, 0, 1, 2, 0, 1, 2, 3, 0, 1, 2, 3, 4, 0, 1, 2, 3, 4, 5};

  // Pass 4: their terms. The energy in double from pass 3's distances (a finite
  // difference of it must hold); the wrench and stiffness in single precision over
  // arrays of the deep points (the loops vectorize), padded with empty points to whole
  // lanes of kLanes, summed per block in the lanes and then in double.
  constexpr std::size_t kLanes = 4;
  const std::size_t lanes = (deeper + kLanes - 1) / kLanes * kLanes;
  const double u = k.metres_per_unit;
  alignas(16) float c[8][kMaxBlockPoints], f[3][kMaxBlockPoints], d[3][kMaxBlockPoints], ka[kMaxBlockPoints],
      push[kMaxBlockPoints];
  for (std::size_t h = 0; h < lanes; ++h) {
    if (h < deeper) {
      const std::size_t i = deep[h];
      float corner[8];
      view.corner_steps(nodes[i], corner);
      for (int q = 0; q < 8; ++q) c[q][h] = corner[q];
      f[0][h] = float(fx[i]), f[1][h] = float(fy[i]), f[2][h] = float(fz[i]);
      d[0][h] = x[i], d[1][h] = y[i], d[2][h] = z[i];
      const double k_a = k.k_area * area[i], phi_m = u * (deep_phi[h] + k.skin);
      sum.term[0] += 0.5 * k_a * phi_m * phi_m;
      sum.depth = std::max(sum.depth, -deep_phi[h]);
      ka[h] = float(k_a), push[h] = float(k_a * phi_m);
    } else {  // an empty point: no stiffness, no push
      for (int q = 0; q < 8; ++q) c[q][h] = 0;
      for (int a = 0; a < 3; ++a) f[a][h] = d[a][h] = 0;
      ka[h] = push[h] = 0;
    }
  }
  const float *dt = map.to_dphi_dt, *a = map.to_arm_f;
  const float arm0[3] = {float(centre_arm.x()), float(centre_arm.y()), float(centre_arm.z())};
  const float uf = float(u);
  alignas(16) float term[kContactTerms][kMaxBlockPoints];
  for (std::size_t h = 0; h < lanes; ++h) {
    // The trilinear distance's gradient (brick steps per fine spacing).
    const float x0 = f[0][h], y0 = f[1][h], z0 = f[2][h];
    const float d00 = c[1][h] - c[0][h], d10 = c[3][h] - c[2][h], d01 = c[5][h] - c[4][h], d11 = c[7][h] - c[6][h];
    const float c00 = c[0][h] + d00 * x0, c10 = c[2][h] + d10 * x0, c01 = c[4][h] + d01 * x0, c11 = c[6][h] + d11 * x0;
    const float c0 = c00 + (c10 - c00) * y0, c1 = c01 + (c11 - c01) * y0;
    const float dx0 = d00 + (d10 - d00) * y0, dx1 = d01 + (d11 - d01) * y0;
    const float grad[3] = {dx0 + (dx1 - dx0) * z0, (c10 - c00) + ((c11 - c01) - (c10 - c00)) * z0, c1 - c0};
    // j = (dphi/dt, dphi/dtheta in metres per radian).
    float j[6], arm[3];
#pragma GCC unroll 3
    for (int r = 0; r < 3; ++r) {
      j[r] = dt[3 * r] * grad[0] + dt[3 * r + 1] * grad[1] + dt[3 * r + 2] * grad[2];
      arm[r] = arm0[r] + a[3 * r] * d[0][h] + a[3 * r + 1] * d[1][h] + a[3 * r + 2] * d[2][h];
    }
    j[3] = uf * (arm[1] * j[2] - arm[2] * j[1]);
    j[4] = uf * (arm[2] * j[0] - arm[0] * j[2]);
    j[5] = uf * (arm[0] * j[1] - arm[1] * j[0]);
    term[0][h] = 0;  // the energy is summed above
#pragma GCC unroll 6
    for (int q = 0; q < 6; ++q) term[kForceTerm + q][h] = -push[h] * j[q];
#pragma GCC unroll 21
    for (int q = 0; q < 21; ++q) term[kStiffnessTerm + q][h] = ka[h] * j[kRow[q]] * j[kColumn[q]];
  }
  // Summed in kLanes lanes, then the lanes in double.
  float lane[kContactTerms][kLanes] = {};
  for (std::size_t h = 0; h < lanes; h += kLanes)
    for (int q = 1; q < kContactTerms; ++q)
      for (std::size_t l = 0; l < kLanes; ++l) lane[q][l] += term[q][h + l];
  for (int q = 1; q < kContactTerms; ++q)
    sum.term[q] += (double(lane[q][0]) + double(lane[q][1])) + (double(lane[q][2]) + double(lane[q][3]));
  sum.points += deeper;
}

}  // namespace

void add_group_contact(const ContactBlocks& points, const ShellChunk& group, const PointMap& map,
                       const Eigen::Vector3d& grid_offset, const Eigen::Vector3d& arm_offset,
                       const SignedDistanceGrid& grid, const FineDistanceView& view, const ContactConstants& k,
                       ContactSum& sum) {
  const double h = grid.fine_spacing();
  const Eigen::Vector3d group_centre = map.to_grid * group.centre + grid_offset;
  if (clear(lower_bound(view, grid, locate(view, grid, group_centre), group_centre), group.radius, k.skin, h)) return;
  // The blocks' centres located and their cells fetched together, then each block
  // tested and evaluated: the tests' reads overlap.
  constexpr std::size_t kBatch = 64;
  Eigen::Vector3d centre[kBatch];
  FineCell cell[kBatch];
  for (std::size_t first = group.begin; first < group.end; first += kBatch) {
    const std::size_t batch = std::min(kBatch, group.end - first);
    for (std::size_t b = 0; b < batch; ++b) {
      centre[b] = map.to_grid * points.blocks[first + b].centre + grid_offset;
      cell[b] = locate(view, grid, centre[b]);
      if (cell[b].node) view.prefetch(cell[b].node);
    }
    for (std::size_t b = 0; b < batch; ++b) {
      const ShellChunk& block = points.blocks[first + b];
      if (clear(lower_bound(view, grid, cell[b], centre[b]), block.radius, k.skin, h)) continue;
      add_block_contact(points, block, map, centre[b], map.to_arm * block.centre + arm_offset, grid, view, k, sum);
    }
  }
}

}  // namespace snapfit
