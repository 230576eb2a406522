// Seed 001's route to the spectra against the grid's, measured:
// 1. ball counts against the grid size m, shaped like seed 001 Table A.2: the Stanford
//    bunny scaled to a box of longest edge 1 (so epsilon = sqrt(3) / (2 m^(1/3)) as there),
//    protrusion mu = 0.25, 0.5, 1; n1 = |A1| and n3 = |A3| (engine/fields/sphere_decomposition.h);
// 2. ball counts and volume errors of the shipped parts (scenes/default.json) against the
//    tolerance;
// 3. time to part 2's spectrum and its error at the 4,096 lowest modes against the exact
//    transform of the mesh's indicator (divergence theorem, in double): the grid path
//    (winding number on the grid + FFT) at several spacings, the spheres path (Algorithm 1
//    + direct NDFT or type-1 NUFFT onto the lattice of the grid path at spacing 0.6) at
//    several tolerances, as a Pareto chart.
//
//   bench_spheres --help lists its options.
// --quick: m up to 2^15, two tolerances and spacings, the lattice of spacing 1.2 (CI proves
// it runs; its figures are not the full run's). The bunny comes
// from the npm package `bunny` (.ci/setup writes build/third_party/bunny/bunny.obj);
// without it part 1 is skipped with a message.
#include <chrono>
#include <cmath>
#include <complex>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "engine/fields/ball_union_error.h"
#include "engine/fields/sphere_decomposition.h"
#include "engine/runtime/device.h"
#include "engine/spectra/ball_spectrum.h"
#include "engine/spectra/mode_order.h"
#include "engine/spectra/spectra.h"
#include "io/mesh_load.h"
#include "mesh/mesh_mass_properties.h"
#include "mesh/procedural/procedural_parts.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "snapfit/error.h"

using namespace snapfit;
namespace fs = std::filesystem;
using Cd = std::complex<double>;

namespace {

double sinc(double x) { return std::abs(x) < 1e-8 ? 1.0 - x * x / 6 : std::sin(x) / x; }

// integral over the closed, outward-wound mesh's solid of exp(-i k.x): by the divergence
// theorem twice, (i / |k|^2) sum_faces (k.n) integral_face exp(-i k.x) dA, each face's
// integral the same in its plane over its edges (sinc per edge).
Cd mesh_indicator_transform(const Mesh& mesh, const Eigen::Vector3d& k, double volume) {
  const double k2 = k.squaredNorm();
  if (k2 == 0) return volume;
  const Cd i(0, 1);
  Cd sum = 0;
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[std::size_t(t[0])], b = mesh.vertices[std::size_t(t[1])],
                          c = mesh.vertices[std::size_t(t[2])];
    const Eigen::Vector3d cross = (b - a).cross(c - a);
    const double area = 0.5 * cross.norm();
    if (area == 0) continue;
    const Eigen::Vector3d n = cross.normalized();
    const double kn = k.dot(n);
    if (kn == 0) continue;
    const Eigen::Vector3d kp = k - kn * n;
    const double size = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
    Cd face;
    if (kp.norm() * size < 1e-4) {
      face = area * std::exp(-i * k.dot((a + b + c) / 3.0));
    } else {
      Cd edges = 0;
      const Eigen::Vector3d p[3] = {a, b, c};
      for (int e = 0; e < 3; ++e) {
        const Eigen::Vector3d d = p[(e + 1) % 3] - p[e], mid = 0.5 * (p[e] + p[(e + 1) % 3]);
        const Eigen::Vector3d m = d.cross(n).normalized();
        edges += kp.dot(m) * d.norm() * std::exp(-i * k.dot(mid)) * sinc(0.5 * kp.dot(d));
      }
      face = i / kp.squaredNorm() * edges;
    }
    sum += kn * face;
  }
  return i / k2 * sum;
}

// Centred in a box of longest edge 1, wound outward (the descriptors' winding number needs it).
Mesh scaled_to_unit_box(Mesh mesh) {
  if (solid_moments(mesh).volume < 0)
    for (auto& t : mesh.triangles) std::swap(t[1], t[2]);
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v);
  const double edge = (box.max() - box.min()).maxCoeff();
  for (auto& v : mesh.vertices) v = (v - box.center()) / edge;
  return mesh;
}

// Seed 001's Table A.2 on the bunny: balls before (n1) and after (n3) reduction against
// the grid size m, for mu = 0.25, 0.5, 1; n3 per mu into `n3`.
nlohmann::json bunny_table(const ComputeContext& ctx, const Mesh& bunny, bool quick, Series (&n3)[3]) {
  DescriptorOptions quiet;
  nlohmann::json table = nlohmann::json::array();
  std::cout << "\nseed 001 Table A.2 shape: the bunny (" << bunny.triangles.size()
            << " triangles) in a box of longest edge 1\n  m       eps      mu=0.25 n1/n3   mu=0.5 n1/n3   "
               "mu=1 n1/n3   fields s\n";
  const std::vector<int> exponents = quick ? std::vector<int>{12, 15} : std::vector<int>{12, 15, 18};
  const double mus[3] = {0.25, 0.5, 1.0};
  for (int i = 0; i < 3; ++i) n3[i].label = "n3, mu = " + bench::fixed(mus[i], 2);
  for (int e : exponents) {
    const double eps = std::sqrt(3.0) / (2.0 * std::cbrt(double(1 << e)));
    const auto t0 = std::chrono::steady_clock::now();
    const GridSpec grid = sphere_grid(bunny, eps);
    DescriptorParams sdf;
    const DescriptorFields f = compute_descriptors(ctx, bunny, grid, sdf, quiet);
    const double field_s = seconds_since(t0);
    nlohmann::json row = {{"m", 1 << e}, {"epsilon", eps}, {"grid_nodes", grid.count()}, {"field_seconds", field_s}};
    std::cout << "  2^" << e << "  " << bench::fixed(eps, 4);
    for (int i = 0; i < 3; ++i) {
      const auto t1 = std::chrono::steady_clock::now();
      const SphereDecomposition d =
          decompose_into_balls(grid, f.winding, f.signed_distance, f.skeletal_density, eps, mus[i]);
      row["mu_" + bench::fixed(mus[i], 2)] = {
          {"n1", d.sampled_balls}, {"n3", d.balls.size()}, {"seconds", seconds_since(t1)}};
      n3[i].x.push_back(double(1 << e));
      n3[i].y.push_back(double(d.balls.size()));
      std::cout << "   " << bench::pad(std::to_string(d.sampled_balls) + "/" + std::to_string(d.balls.size()), 13);
    }
    std::cout << "  " << bench::fixed(field_s, 1) << "\n";
    table.push_back(row);
  }
  return table;
}

Chart bunny_chart(const Series (&n3)[3]) {
  Chart chart = bench::make_chart("Balls n3 against grid size m (the bunny, seed 001 Table A.2 shape)",
                                  "m (grid nodes)", "balls n3", true, true);
  for (const auto& s : n3) chart.series.push_back(s);
  chart.series.push_back({"seed 001 Table A.2, mu = 0.25",
                          {4096, 32768, 262144, 2097152},
                          {36, 161, 1024, 3686},
                          Series::Style::points,
                          ""});
  return chart;
}

// The shipped parts' decompositions at a few tolerances, with their error against the solid.
nlohmann::json shipped_parts(const ComputeContext& ctx, const Scene& scene, const Mesh (&parts)[2], bool quick) {
  DescriptorOptions quiet;
  const std::vector<double> tolerances = quick ? std::vector<double>{2.0, 1.0} : std::vector<double>{2.0, 1.0, 0.5};
  nlohmann::json shipped = nlohmann::json::array();
  std::cout << "\nshipped parts (scenes/default.json): tolerance, balls n3 (n1), volume error (95% interval), s\n";
  for (int p = 0; p < 2; ++p)
    for (double t : tolerances) {
      SphereDecompositionParams params;
      params.tolerance = t;
      const SphereDecomposition d = decompose_part(ctx, parts[p], scene.descriptor, params, quiet);
      const BallUnionError e = ball_union_error(ctx, parts[p], d.balls, quick ? 50000 : 400000);
      std::cout << "  part " << p + 1 << "  " << t << " mm: " << d.balls.size() << " (" << d.sampled_balls << "), "
                << bench::fixed(100 * e.volume_error / e.solid_volume, 2) << "% ["
                << bench::fixed(100 * e.volume_error_low / e.solid_volume, 2) << ", "
                << bench::fixed(100 * e.volume_error_high / e.solid_volume, 2) << "], Hausdorff sampled "
                << bench::fixed(e.hausdorff_sampled, 3) << " <= " << t << ", " << bench::fixed(d.seconds, 2) << " s\n";
      shipped.push_back({{"part", p + 1},
                         {"tolerance", t},
                         {"balls", d.balls.size()},
                         {"sampled_balls", d.sampled_balls},
                         {"relative_volume_error", e.volume_error / e.solid_volume},
                         {"hausdorff_sampled", e.hausdorff_sampled},
                         {"seconds", d.seconds}});
    }
  return shipped;
}

// A spectrum's point on the Pareto chart: how it was made, at which spacing or tolerance,
// its time and its error.
struct Point {
  std::string path;
  double setting, seconds, error;
};

constexpr std::size_t kModes = 4096;

// Relative L2 error of S (`rho` on `s`'s lattice) at the kModes lowest modes against the
// peg's exact transform i F(2 pi w) e^{2 pi i w.c}.
double spectrum_error(const Mesh& peg, double volume, const PairSpectra& s, const std::vector<Complex>& rho,
                      const Eigen::Vector3d& centre) {
  const std::vector<std::size_t> order = mode_order(s);
  double num = 0, den = 0;
  for (std::size_t i = 0; i < std::min(kModes, order.size()); ++i) {
    const auto k = signed_node(s.dims, order[i]);
    const Eigen::Vector3d w(k[0] / s.length.x(), k[1] / s.length.y(), k[2] / s.length.z());
    const Cd exact =
        Cd(0, 1) * mesh_indicator_transform(peg, 2 * M_PI * w, volume) * std::polar(1.0, 2 * M_PI * w.dot(centre));
    num += std::norm(Cd(rho[order[i]]) - exact);
    den += std::norm(exact);
  }
  return std::sqrt(num / den);
}

// The grid path: the peg's indicator sampled at several spacings and transformed.
void add_grid_points(const FftLibrary& fft, const ComputeContext& ctx, const Mesh& peg,
                     const DescriptorParams& indicator, bool quick, std::vector<Point>& points) {
  DescriptorOptions quiet;
  const double volume = std::abs(solid_moments(peg).volume);
  const std::vector<double> spacings =
      quick ? std::vector<double>{1.6, 1.2} : std::vector<double>{1.6, 1.2, 0.8, 0.6, 0.4};
  for (double h : spacings) {
    GridParams gp;
    gp.spacing = h;
    gp.padding = 5;
    const GridSpec grid = make_grid(Eigen::AlignedBox3d(Eigen::Vector3d(-5, -5, 0), Eigen::Vector3d(5, 5, 30)), gp);
    const auto t0 = std::chrono::steady_clock::now();
    const DescriptorFields f = compute_descriptors(ctx, peg, grid, indicator, quiet);
    const std::vector<float> values = affinity_imaginary(f);
    std::vector<Complex> samples(values.size());
    for (std::size_t i = 0; i < values.size(); ++i) samples[i] = Complex(0, values[i]);
    SpectrumOptions so;
    so.exact_rotation_width = 0;
    const PairSpectra s = compute_pair_spectra(fft, ctx, grid, samples, grid, samples, so);
    // Both parts' FFTs ran; one part's share is half the spectra time.
    const double seconds = seconds_since(t0) - 0.5 * s.seconds;
    const double error = spectrum_error(peg, volume, s, s.part2.rho, s.part2.centre);
    points.push_back({"grid", h, seconds, error});
    std::cout << "  grid    spacing " << h << ": " << bench::fixed(seconds, 2) << " s, error "
              << bench::fixed(100 * error, 3) << "%\n";
  }
}

// The spheres path on the lattice of the reference spacing's box: the peg's balls at
// several tolerances, their spectrum summed directly and by the NUFFT.
void add_sphere_points(const FftLibrary& fft, const ComputeContext& ctx, const Mesh& peg,
                       const DescriptorParams& descriptor, const GridSpec& reference_grid, bool quick,
                       std::vector<Point>& points) {
  DescriptorOptions quiet;
  const double volume = std::abs(solid_moments(peg).volume);
  // The spheres path on the lattice of the reference spacing's box.
  std::vector<Complex> zero(reference_grid.count(), Complex(0, 0));
  SpectrumOptions so;
  so.exact_rotation_width = 0;
  const PairSpectra lattice_of = compute_pair_spectra(fft, ctx, reference_grid, zero, reference_grid, zero, so);
  FrequencyLattice lattice;
  lattice.dims = lattice_of.dims;
  lattice.length = lattice_of.length;
  lattice.centre = lattice_of.part2.centre;
  const std::vector<double> sphere_tolerances =
      quick ? std::vector<double>{2.0, 1.0} : std::vector<double>{2.0, 1.0, 0.7, 0.5};
  for (double t : sphere_tolerances) {
    SphereDecompositionParams params;
    params.tolerance = t;
    const SphereDecomposition d = decompose_part(ctx, peg, descriptor, params, quiet);
    double ball_volume = 0;
    for (const Ball& b : d.balls) ball_volume += ball_transform(b.radius, 0);
    const double weight = volume / ball_volume;
    for (const std::string method : {"direct", "nufft"}) {
      const auto t0 = std::chrono::steady_clock::now();
      const std::vector<std::complex<float>> values = method == "direct"
                                                          ? ball_spectrum_direct(ctx, d.balls, lattice)
                                                          : ball_spectrum_nufft(fft, ctx, d.balls, lattice);
      const double seconds = d.seconds + seconds_since(t0);
      std::vector<Complex> rho(values.size());
      for (std::size_t k = 0; k < values.size(); ++k) rho[k] = Complex(0, float(weight)) * values[k];
      const double error = spectrum_error(peg, volume, lattice_of, rho, lattice.centre);
      points.push_back({"spheres " + method, t, seconds, error});
      std::cout << "  spheres " << method << " tolerance " << t << " (" << d.balls.size() << " balls onto "
                << lattice.count() << " modes): " << bench::fixed(seconds, 2) << " s, error "
                << bench::fixed(100 * error, 3) << "%\n";
    }
  }
}

Chart pareto_chart(const std::vector<Point>& points) {
  Chart pareto = bench::make_chart("Part 2 (peg) spectrum: error at the 4,096 lowest modes against time",
                                   "seconds to the spectrum", "relative L2 error", true, true);
  for (const std::string path : {"grid", "spheres direct", "spheres nufft"}) {
    Series s{path, {}, {}, Series::Style::points, ""};
    for (const Point& p : points)
      if (p.path == path) {
        s.x.push_back(p.seconds);
        s.y.push_back(p.error);
      }
    pareto.series.push_back(s);
  }
  return pareto;
}

}  // namespace

int main(int argc, char** argv) {
  return bench::guarded_main("bench_spheres", [&] {
    bool quick = false;
    std::string device_spec, out_dir = "results/bench_spheres", bunny_path = "build/third_party/bunny/bunny.obj";
    CLI::App app{
        "Spherical decompositions (seed 001 Table A.2 shape) and the time and error of spectra from balls "
        "against the grid path",
        "bench_spheres"};
    bench::add_common_options(app, quick, device_spec, out_dir);
    app.add_option("--bunny", bunny_path, "the Stanford bunny's mesh");
    bench::parse(app, argc, argv);
    const std::string load_start = bench::read_loadavg();
    const ComputeContext ctx = make_compute_context(select_device(device_spec_from(device_spec)));
    std::cout << "device " << describe_device(ctx.device.info) << "\n";
    const FftLibrary fft;
    nlohmann::json report = {{"command", bench::command_line(argc, argv)}, {"date", bench::now_iso()}};
    std::vector<Chart> charts;

    // 1. Table A.2 on the bunny.
    if (!fs::exists(bunny_path)) {
      std::cout << "bunny: " << bunny_path << " is missing (bash .ci/setup fetches the npm package bunny): skipped\n";
      report["bunny"] = "skipped: " + bunny_path + " missing";
    } else {
      Series n3[3];
      report["bunny"] = bunny_table(ctx, scaled_to_unit_box(load_mesh(bunny_path)), quick, n3);
      charts.push_back(bunny_chart(n3));
    }

    // 2. The shipped parts.
    const Scene scene = load_scene("scenes/default.json");
    const Mesh parts[2] = {make_procedural_part(*scene.part1.procedural),
                           make_procedural_part(*scene.part2.procedural)};
    report["shipped_parts"] = shipped_parts(ctx, scene, parts, quick);

    // 3. Part 2's (the peg's) spectrum: time and error at the 4,096 lowest modes against
    //    the exact transform, on the lattice of the scene's FFT box at spacing 0.6.
    const Mesh& peg = parts[1];
    GridParams reference_params;
    reference_params.spacing = quick ? 1.2 : 0.6;
    reference_params.padding = 5;
    const GridSpec reference_grid =
        make_grid(Eigen::AlignedBox3d(Eigen::Vector3d(-5, -5, 0), Eigen::Vector3d(5, 5, 30)), reference_params);
    DescriptorParams indicator;
    indicator.kind = DescriptorKind::indicator;
    std::vector<Point> points;
    std::cout << "\npart 2 (peg) spectrum at the " << kModes << " lowest modes against the exact transform:\n";
    add_grid_points(fft, ctx, peg, indicator, quick, points);
    add_sphere_points(fft, ctx, peg, scene.descriptor, reference_grid, quick, points);
    nlohmann::json jpoints = nlohmann::json::array();
    const Chart pareto = pareto_chart(points);
    for (const Point& p : points)
      jpoints.push_back({{"path", p.path}, {"setting", p.setting}, {"seconds", p.seconds}, {"error", p.error}});
    charts.push_back(pareto);
    report["spectra"] = jpoints;
    report["load_average"] = {{"start", load_start}, {"end", bench::read_loadavg()}};
    fs::create_directories(out_dir);
    std::ofstream(fs::path(out_dir) / "spheres.json") << report.dump(2) << "\n";
    const std::string page =
        bench::write_charts(out_dir, "bench_spheres: spherical decompositions and spectra from balls",
                            bench::command_line(argc, argv), charts);
    std::cout << "wrote " << out_dir << "/spheres.json and " << page << "\n";
    return 0;
  });
}
