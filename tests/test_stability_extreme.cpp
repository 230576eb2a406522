// Extreme poses and scales with the real engine, on the small zero-clearance
// peg-and-hole pair (tests/stability_support.h): exact contact, deep interpenetration,
// rotations near 180 degrees and translations at the edge of the padded box give finite
// energy, force and torque that agree with central differences of the engine's own
// energy; beyond the box the result is zero and flagged, never an aliased wrap-around
// force; and the same scene scaled from micrometres to kilometres gives E ~ L^3,
// F ~ L^2, T ~ L^3.
#include <cmath>
#include <doctest/doctest.h>
#include <iostream>
#include <limits>
#include <map>
#include <utility>

#include "engine/query/query_engine.h"
#include "scheduler/haptics/virtual_coupling.h"
#include "tests/stability_support.h"

using namespace snapfit;
using Eigen::Vector3d;

namespace {

using test::pose_at;

struct Differences {
  QueryResult at;
  Vector3d force = Vector3d::Zero(), torque = Vector3d::Zero();  // -dE/dt, -dE/dtheta by central differences
};

Differences differences(QueryEngine& engine, const Pose& pose, double h, double angle) {
  std::vector<Pose> batch = {pose};
  for (int a = 0; a < 3; ++a)
    for (double s : {1.0, -1.0}) {
      Pose p = pose;
      p.translation[a] += s * h;
      batch.push_back(p);
    }
  for (int a = 0; a < 3; ++a)
    for (double s : {1.0, -1.0}) {
      Pose p = pose;
      p.rotation = (rotation_exp(s * angle * Vector3d::Unit(a)) * pose.rotation).normalized();
      batch.push_back(p);
    }
  const std::vector<QueryResult> r = engine.query_batch(batch);
  Differences d;
  d.at = r[0];
  for (int a = 0; a < 3; ++a) {
    d.force[a] = -(r[1 + 2 * a].energy - r[2 + 2 * a].energy) / (2 * h);
    d.torque[a] = -(r[7 + 2 * a].energy - r[8 + 2 * a].energy) / (2 * angle);
  }
  return d;
}

struct SmallEngine {
  AssemblyPair pair;
  std::unique_ptr<QueryEngine> engine;
};

SmallEngine small_engine(const test::SmallPairParams& params, std::size_t modes) {
  SmallEngine s;
  s.pair = test::build_small_pair(test::small_peg_hole_scene(params), params.oversampling);
  s.engine = make_query_engine(test::test_context(), s.pair.spectra,
                               query_variant_for(s.pair.scene, Interpolation::tricubic), test::test_program_cache());
  s.engine->set_modes(modes);
  return s;
}

}  // namespace

TEST_CASE(
    "stability extreme: contact, interpenetration, near-180-degree rotations and the box edge are finite and match the "
    "energy's differences") {
  SmallEngine s = small_engine({}, 4096);
  QueryEngine& engine = *s.engine;
  const double h = s.pair.spectra.spacing;

  // The edge of the padded box along +x and -z: the last translation the engine accepts
  // (bisection on the flag), so the part's box just touches an image of part 1's box.
  auto edge = [&](const Vector3d& dir, const Pose& from) {
    double lo = 0, hi = 1e3;
    for (int i = 0; i < 60; ++i) {
      const double mid = 0.5 * (lo + hi);
      Pose p = from;
      p.translation += mid * dir;
      (engine.query(p).flags == query_ok ? lo : hi) = mid;
    }
    return lo;
  };
  const Pose centre = pose_at({0, 0, 0});
  const double edge_x = edge(Vector3d::UnitX(), centre), edge_z = edge(-Vector3d::UnitZ(), centre);
  std::cout << "extreme: box edge at x = " << edge_x << ", z = " << -edge_z << " (spacing " << h << ", FFT box "
            << s.pair.spectra.length.transpose() << ")\n";
  REQUIRE(edge_x > 1);
  REQUIRE(edge_z > 1);

  struct Case {
    const char* name;
    Pose pose;
  };
  const std::vector<Case> cases = {
      {"zero clearance, assembled: exact contact on the walls and the hole's bottom", pose_at({0, 0, -20})},
      {"zero clearance, half inserted", pose_at({0, 0, -10})},
      {"exact contact on the block's top face, beside the hole", pose_at({10, 0, 0})},
      {"deep interpenetration: peg pushed 10 mm through the hole's bottom", pose_at({0, 0, -30})},
      {"deep interpenetration: peg sunk sideways into solid block", pose_at({9, 0, -12}, 20)},
      {"peg through and out of the block's bottom", pose_at({0, 0, -42})},
      {"rotation 179 deg about x", pose_at({0, 0, 8}, 179, Vector3d::UnitX())},
      {"rotation 179.99 deg about (1,1,1)", pose_at({1, 0, 6}, 179.99, Vector3d(1, 1, 1))},
      {"rotation exactly 180 deg about y (w = 0)", pose_at({0, 0, 10}, 180)},
      {"rotation -179.99 deg about (1,-2,0.5)", pose_at({0, 1, 9}, -179.99, Vector3d(1, -2, 0.5))},
      {"upside down, pushed into the hole", pose_at({0, 0, -5}, 180, Vector3d::UnitX())},
      {"at the edge of the padded box, +x", pose_at({0.999 * edge_x, 0, 0})},
      {"at the edge of the padded box, -z", pose_at({0, 0, -0.999 * edge_z})},
  };
  // Scales: the largest force and torque over the cases (relative errors of near-zero
  // wrenches, e.g. at symmetric poses, would measure noise against nothing).
  std::vector<Differences> d;
  double f_scale = 0, t_scale = 0;
  for (const Case& c : cases) {
    d.push_back(differences(engine, c.pose, 1e-2 * h, 1e-3));
    f_scale = std::max(f_scale, d.back().at.force.norm());
    t_scale = std::max(t_scale, d.back().at.torque.norm());
  }
  REQUIRE(f_scale > 0);
  REQUIRE(t_scale > 0);
  double worst_f = 0, worst_t = 0;
  for (std::size_t n = 0; n < cases.size(); ++n) {
    CAPTURE(cases[n].name);
    const QueryResult& q = d[n].at;
    REQUIRE(q.flags == query_ok);
    CHECK(std::isfinite(q.energy));
    CHECK(q.force.allFinite());
    CHECK(q.torque.allFinite());
    const double ef = (q.force - d[n].force).norm() / f_scale, et = (q.torque - d[n].torque).norm() / t_scale;
    std::cout << "extreme: " << cases[n].name << ": E " << q.energy << ", |F| " << q.force.norm() << ", |T| "
              << q.torque.norm() << "; |F - FD| / max|F| " << ef << ", |T - FD| / max|T| " << et << "\n";
    worst_f = std::max(worst_f, ef);
    worst_t = std::max(worst_t, et);
    CHECK(ef < 1e-3);
    CHECK(et < 1e-2);
  }
  std::cout << "extreme: worst |F - FD| / max|F| " << worst_f << ", |T - FD| / max|T| " << worst_t << "\n";
}

TEST_CASE("stability extreme: beyond the padded box the query is zero and flagged, never an aliased force") {
  SmallEngine s = small_engine({}, 4096);
  QueryEngine& engine = *s.engine;
  const PairSpectra& sp = s.pair.spectra;
  // Part 2 moved by a whole FFT period lands exactly on an image of part 1 in the
  // periodic sum: without the guard it would feel the same force as at the original pose.
  const Pose inside = pose_at({1, 0, -8}, 2);
  const QueryResult ref = engine.query(inside);
  REQUIRE(ref.flags == query_ok);
  REQUIRE(ref.force.norm() > 0);
  for (int a = 0; a < 3; ++a)
    for (double k : {-2.0, -1.0, 1.0, 2.0}) {
      Pose p = inside;
      p.translation[a] += k * sp.length[a];
      const QueryResult r = engine.query(p);
      CAPTURE(p.translation.transpose());
      CHECK((r.flags & query_outside_grid) != 0);
      CHECK(r.energy == 0);
      CHECK(r.force == Vector3d::Zero());
      CHECK(r.torque == Vector3d::Zero());
    }
  // Far beyond float range of the kernel's inputs, and beyond double's exact integers.
  for (double far : {1e7, 1e20, 1e300}) {
    const QueryResult r = engine.query(pose_at({far, -far, far}, 45, {1, 2, 3}));
    CHECK((r.flags & query_outside_grid) != 0);
    CHECK(r.force == Vector3d::Zero());
  }
  // Just past the edge (the bisected limit + one micrometre): flagged; the flag rises at
  // the limit, so the energy never ramps through a partially aliased region.
  double lo = 0, hi = 1e3;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (engine.query(pose_at({mid, 0, 0})).flags == query_ok ? lo : hi) = mid;
  }
  CHECK((engine.query(pose_at({lo + 1e-3, 0, 0})).flags & query_outside_grid) != 0);
  const QueryResult last = engine.query(pose_at({lo, 0, 0}));
  CHECK(last.flags == query_ok);
  // At the edge the part is far from part 1 (the boxes are padded): the energy there is
  // the far-field value, small against contact.
  CHECK(std::abs(last.energy) < 0.05 * std::abs(engine.query(pose_at({0, 0, -20})).energy));
}

TEST_CASE("stability extreme: the same scene in micrometres and in kilometres scales as E ~ L^3, F ~ L^2, T ~ L^3") {
  // Lengths multiplied by s, scene units unchanged (mm), so the numbers span 1e-3 ..
  // 3e7. s = 2^-10 and 2^20 (about um and km sizes) scale every coordinate exactly (as
  // does mm, s = 1, which the other extreme tests cover), so any absolute epsilon or
  // overflow anywhere in the pipeline would show: measured identical results (difference
  // 0), and that is asserted.
  //
  // s = 1e-3 and 1e6 (exactly um and km) perturb the geometry by round-off. The
  // descriptors work in grid units (engine/fields/descriptors.cpp), so that is all they see:
  // before they did, grid points on the block's faces flipped between the winding
  // number's one-sided values and E differed by up to 6% at contact poses. Round-off
  // still breaks ties in the hierarchy's splits differently, so the quadrature clusters
  // differ and so do the quadrature errors, each within its bound: asserted per grid
  // point, |s_a - s_b| <= bound_a + bound_b, and w the same off the surface. E, F and T
  // differ accordingly; measured: at most 5.9e-4 of the largest E, 2.5e-3 of the largest
  // F and 1.4e-2 of the largest T over these poses (reported, not bounded).
  const std::vector<Pose> poses = {pose_at({1, 0, -8}, 2), pose_at({0.5, 0.3, 2}, 10, {1, 1, 0}), pose_at({0, 0, -20}),
                                   pose_at({4, -3, 12}, 170, {0, 1, 1})};
  std::map<double, SmallEngine> runs;
  std::map<double, std::vector<QueryResult>> results;
  for (double scale : {std::ldexp(1.0, -10), std::ldexp(1.0, 20), 1e-3, 1e6}) {
    test::SmallPairParams params;
    params.scale = scale;
    runs[scale] = small_engine(params, 4096);
    std::vector<Pose> scaled = poses;
    for (Pose& p : scaled) p.translation *= scale;
    results[scale] = runs[scale].engine->query_batch(scaled);
  }
  // Largest relative differences of b (at scale lb) from a (at scale la) in E, F and T,
  // after the L^3, L^2, L^3 scaling, each against its largest value over the poses.
  auto compare = [&](double la, double lb, const char* what) {
    const std::vector<QueryResult>& a = results[la];
    const std::vector<QueryResult>& b = results[lb];
    const double r = lb / la;
    double e_scale = 0, f_scale = 0, t_scale = 0;
    for (const QueryResult& q : a) {
      e_scale = std::max(e_scale, std::abs(q.energy));
      f_scale = std::max(f_scale, q.force.norm());
      t_scale = std::max(t_scale, q.torque.norm());
    }
    Vector3d worst = Vector3d::Zero();
    for (std::size_t n = 0; n < poses.size(); ++n) {
      CAPTURE(what);
      CAPTURE(n);
      REQUIRE(a[n].flags == query_ok);
      REQUIRE(b[n].flags == query_ok);
      worst = worst.cwiseMax(Vector3d(std::abs(b[n].energy / (r * r * r) - a[n].energy) / e_scale,
                                      (b[n].force / (r * r) - a[n].force).norm() / f_scale,
                                      (b[n].torque / (r * r * r) - a[n].torque).norm() / t_scale));
    }
    std::cout << "scale: " << what << ": largest differences in E, F, T over their largest values " << worst.x() << ", "
              << worst.y() << ", " << worst.z() << "\n";
    return worst;
  };
  CHECK(compare(std::ldexp(1.0, -10), std::ldexp(1.0, 20), "2^-10 (um-sized) vs 2^20 (km-sized), exact scaling") ==
        Vector3d::Zero());
  compare(std::ldexp(1.0, -10), 1e-3, "2^-10 vs 1e-3 (exactly um)");
  compare(std::ldexp(1.0, 20), 1e6, "2^20 vs 1e6 (exactly km)");

  // The fields of both parts agree within the sum of their quadrature bounds, and the
  // winding numbers agree off the surface (where w is not within round-off of 1/2).
  for (const auto& [la, lb] : {std::pair{std::ldexp(1.0, -10), 1e-3}, std::pair{std::ldexp(1.0, 20), 1e6}}) {
    for (int part = 1; part <= 2; ++part) {
      const DescriptorFields& a = (part == 1 ? runs[la].pair.fields1 : runs[la].pair.fields2).fields;
      const DescriptorFields& b = (part == 1 ? runs[lb].pair.fields1 : runs[lb].pair.fields2).fields;
      CAPTURE(la);
      CAPTURE(lb);
      CAPTURE(part);
      REQUIRE(a.grid.dims == b.grid.dims);
      std::size_t outside_bounds = 0, winding_flips = 0, on_surface = 0;
      double largest_ratio = 0;
      for (std::size_t i = 0; i < a.winding.size(); ++i) {
        const double ds = std::abs(static_cast<double>(a.skeletal_density[i]) - b.skeletal_density[i]);
        const double allowed = static_cast<double>(a.density_bound[i]) + b.density_bound[i];
        // Float summation of the same terms in another order: a few ulps of |s|.
        const double rounding = 64 * std::numeric_limits<float>::epsilon() * std::abs(a.skeletal_density[i]);
        if (ds > allowed + rounding) ++outside_bounds;
        if (allowed > 0) largest_ratio = std::max(largest_ratio, ds / allowed);
        const bool surface = std::abs(a.winding[i] - 0.5f) < 1e-3f || std::abs(b.winding[i] - 0.5f) < 1e-3f;
        on_surface += surface;
        if (!surface && a.winding[i] != b.winding[i]) ++winding_flips;
      }
      std::cout << "scale: part " << part << ", " << la << " vs " << lb << ": density differences at most "
                << largest_ratio << " of the summed bounds; " << on_surface << " grid points on the surface\n";
      CHECK(outside_bounds == 0);
      CHECK(winding_flips == 0);
    }
  }
}
