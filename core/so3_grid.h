#pragma once
// A deterministic, uniform grid of rotations: the Hopf fibration of SO(3) over S^2
// (Yershova, Jain, LaValle, Mitchell, IJRR 2010, "Generating uniform incremental grids
// on SO(3) using the Hopf fibration"). A rotation is R = Rz(phi) Ry(theta) Rz(psi): the
// point (theta, phi) of S^2 is where R sends the z axis, psi the turn about it. The
// uniform measure is d(cos theta) dphi dpsi, so an equal-area partition of S^2 times
// equally spaced psi samples SO(3) uniformly. For S^2 we take Leopardi's recursive zonal
// equal-area partition (Leopardi, ETNA 25, 2006): two polar caps centred on the poles and
// collars of equal-area cells between them, whose centres are the base points; with
// psi_k = 2 pi k / M the grid holds the identity and the half turns that flip z.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <vector>

namespace snapfit {

struct So3Grid {
  std::vector<Eigen::Quaterniond> rotations;  // base cell by base cell, psi fastest
  std::size_t base_cells = 0;                 // cells of the S^2 partition
  std::size_t psi_steps = 0;                  // samples of the turn about each base point
  double step_rad = 0;                        // the spacing the grid was built for
};

// The centres of Leopardi's partition of S^2 into n equal-area cells (unit vectors,
// north cap first). Throws snapfit::Error for n = 0.
std::vector<Eigen::Vector3d> equal_area_sphere_points(std::size_t n);

// A grid with neighbouring rotations about `step_rad` apart: base cells of area step^2
// (n = round(4 pi / step^2)) and psi spacing of at most step. Throws snapfit::Error for a
// step outside (0, pi].
So3Grid so3_grid_for_step(double step_rad);
// A grid with about `count` rotations (the product of base cells and psi steps nearest
// it, at the spacing (8 pi^2 / count)^(1/3) that `count` uniform rotations would have).
// Throws snapfit::Error for count = 0.
So3Grid so3_grid_for_count(std::size_t count);

// The angle of the rotation a^-1 b, in [0, pi].
double rotation_distance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

// The covering radius of the grid (the largest angle from any rotation to its nearest
// grid rotation), estimated as the largest nearest-grid angle over `probes` rotations of
// a finer grid of the same kind plus a local ascent from the worst of them. It is a lower
// bound on the true radius that converges as the probes get denser.
double so3_covering_radius(const So3Grid& grid, std::size_t probes = 200000);

}  // namespace snapfit
