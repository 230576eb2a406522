#include "core/so3_grid.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <string>

#include "snapfit/error.h"

namespace snapfit {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Colatitude of the polar cap of area `area` on the unit sphere: 2 pi (1 - cos theta) = area.
double cap_colatitude(double area) { return std::acos(std::clamp(1.0 - area / (2 * kPi), -1.0, 1.0)); }

Eigen::Quaterniond hopf_rotation(const Eigen::Vector3d& base, double psi) {
  const double theta = std::acos(std::clamp(base.z(), -1.0, 1.0));
  const double phi = std::atan2(base.y(), base.x());
  return Eigen::AngleAxisd(phi, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitY()) *
         Eigen::AngleAxisd(psi, Eigen::Vector3d::UnitZ());
}

So3Grid make_grid(std::size_t base_cells, std::size_t psi_steps, double step) {
  So3Grid grid;
  const std::vector<Eigen::Vector3d> bases = equal_area_sphere_points(base_cells);
  grid.base_cells = bases.size();
  grid.psi_steps = psi_steps;
  grid.step_rad = step;
  grid.rotations.reserve(bases.size() * psi_steps);
  for (const Eigen::Vector3d& b : bases)
    for (std::size_t k = 0; k < psi_steps; ++k) grid.rotations.push_back(hopf_rotation(b, 2 * kPi * k / psi_steps));
  return grid;
}

// Nearest-grid angle of q. A rotation by angle a moves z by at most a, so the grid
// rotation nearest q lies over a base point within that angle of q z: after the ring
// over the nearest base point, only rings over base points closer than the best so far
// can hold a nearer rotation.
struct NearestRotation {
  const So3Grid& grid;
  std::vector<Eigen::Vector3d> bases;
  explicit NearestRotation(const So3Grid& g) : grid(g) {
    for (std::size_t c = 0; c < g.base_cells; ++c)
      bases.push_back(g.rotations[c * g.psi_steps] * Eigen::Vector3d::UnitZ());
  }
  double ring(const Eigen::Quaterniond& q, std::size_t c) const {
    double best = kPi;
    for (std::size_t k = 0; k < grid.psi_steps; ++k)
      best = std::min(best, rotation_distance(q, grid.rotations[c * grid.psi_steps + k]));
    return best;
  }
  double operator()(const Eigen::Quaterniond& q, std::vector<double>& dots) const {
    const Eigen::Vector3d z = q * Eigen::Vector3d::UnitZ();
    dots.resize(bases.size());
    std::size_t nearest = 0;
    for (std::size_t c = 0; c < bases.size(); ++c) {
      dots[c] = bases[c].dot(z);
      if (dots[c] > dots[nearest]) nearest = c;
    }
    double best = ring(q, nearest);
    for (std::size_t c = 0; c < bases.size(); ++c)
      if (c != nearest && dots[c] > std::cos(best)) best = std::min(best, ring(q, c));
    return best;
  }
};

}  // namespace

std::vector<Eigen::Vector3d> equal_area_sphere_points(std::size_t n) {
  if (n == 0) throw Error("equal_area_sphere_points: the number of cells must be positive");
  if (n == 1) return {Eigen::Vector3d::UnitZ()};
  const double area = 4 * kPi / double(n);
  const double cap = cap_colatitude(area);
  std::vector<std::size_t> collar_cells;  // Leopardi's rounding with carry of the ideal counts
  if (n > 2) {
    const double ideal_collars = (kPi - 2 * cap) / std::sqrt(area);
    const std::size_t collars = std::max<std::size_t>(1, std::size_t(std::lround(ideal_collars)));
    const double fitting = (kPi - 2 * cap) / double(collars);
    double carry = 0;
    for (std::size_t i = 0; i < collars; ++i) {
      const double a = cap + fitting * double(i), b = a + fitting;
      const double ideal = 2 * kPi * (std::cos(a) - std::cos(b)) / area;
      const long m = std::lround(ideal + carry);
      carry += ideal - double(m);
      collar_cells.push_back(std::size_t(std::max(1L, m)));
    }
  }
  std::vector<Eigen::Vector3d> points{Eigen::Vector3d::UnitZ()};
  std::size_t before = 1;  // cells above the collar
  for (std::size_t i = 0; i < collar_cells.size(); ++i) {
    // The collar's edges hold the cumulative area of the cells above them exactly.
    const double top = cap_colatitude(area * double(before));
    const double bottom = cap_colatitude(area * double(before + collar_cells[i]));
    const double theta = 0.5 * (top + bottom);
    const std::size_t m = collar_cells[i];
    const double offset = (i % 2 == 0) ? 0.5 : 0.0;  // alternate collars half a cell apart
    for (std::size_t j = 0; j < m; ++j) {
      const double phi = 2 * kPi * (double(j) + offset) / double(m);
      points.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
    before += m;
  }
  points.push_back(-Eigen::Vector3d::UnitZ());
  points.resize(std::min(points.size(), n));  // n = 2: the two caps
  return points;
}

So3Grid so3_grid_for_step(double step) {
  if (!(step > 0 && step <= kPi)) throw Error("SO(3) grid: the step must be in (0, 180] degrees");
  const std::size_t base = std::max<std::size_t>(1, std::size_t(std::lround(4 * kPi / (step * step))));
  const std::size_t psi = std::max<std::size_t>(1, std::size_t(std::ceil(2 * kPi / step - 1e-9)));
  return make_grid(base, psi, step);
}

So3Grid so3_grid_for_count(std::size_t count) {
  if (count == 0) throw Error("SO(3) grid: the number of rotations must be positive");
  const double step = std::min(kPi, std::cbrt(8 * kPi * kPi / double(count)));
  const std::size_t base = std::max<std::size_t>(1, std::size_t(std::lround(4 * kPi / (step * step))));
  const std::size_t psi = std::max<std::size_t>(1, std::size_t(std::lround(double(count) / double(base))));
  return make_grid(base, psi, step);
}

double rotation_distance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  const double c = std::abs(a.normalized().dot(b.normalized()));
  return 2 * std::acos(std::min(1.0, c));
}

double so3_covering_radius(const So3Grid& grid, std::size_t probes) {
  if (grid.rotations.empty()) throw Error("SO(3) grid: no rotations");
  // Probes: a finer grid of the same kind turned off the grid's symmetry axes.
  const So3Grid fine = so3_grid_for_count(std::max<std::size_t>(probes, 8 * grid.rotations.size()));
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.3711, Eigen::Vector3d(0.43, -0.61, 0.67).normalized()));
  const NearestRotation nearest(grid);
  std::vector<double> order;
  std::vector<std::pair<double, Eigen::Quaterniond>> worst;
  for (const Eigen::Quaterniond& p : fine.rotations) {
    const Eigen::Quaterniond q = turn * p;
    worst.emplace_back(nearest(q, order), q);
  }
  const std::size_t keep = std::min<std::size_t>(16, worst.size());
  std::partial_sort(worst.begin(), worst.begin() + keep, worst.end(),
                    [](const auto& a, const auto& b) { return a.first > b.first; });
  double radius = worst.front().first;
  // Local ascent of the nearest-grid angle from the worst probes (small turns about x, y, z).
  for (std::size_t i = 0; i < keep; ++i) {
    auto [value, q] = worst[i];
    for (double h = fine.step_rad; h > 1e-4; h *= 0.5) {
      bool moved = true;
      while (moved) {
        moved = false;
        for (int axis = 0; axis < 3; ++axis)
          for (double sign : {-1.0, 1.0}) {
            const Eigen::Quaterniond trial =
                Eigen::Quaterniond(Eigen::AngleAxisd(sign * h, Eigen::Vector3d::Unit(axis))) * q;
            const double v = nearest(trial, order);
            if (v > value + 1e-12) {
              value = v;
              q = trial;
              moved = true;
            }
          }
      }
    }
    radius = std::max(radius, value);
  }
  return radius;
}

}  // namespace snapfit
