// Benchmark of descriptor precomputation (engine/fields/descriptors.h compute_descriptors):
// distance, winding number and skeletal density of one part on a uniform grid, on the
// selected OpenCL device.
//
//   bench_descriptors --help lists its options.
//
// Cases (all on the procedural three_peg_base of scenes/three_pegs.json - a CAD-like
// part with flat faces, cylinders and toroidal fillets - whose triangle count is set by
// its `segments`):
//   m_sweep     time against grid points m at fixed triangle count n
//   n_sweep     time against n at fixed m
//   brute       the paper's brute-force O(m n) density (DescriptorOptions::brute_force_density)
//               against the hierarchical one on the same grid: speed-up and
//               max |s_h - s_b| / (bound_h + bound_b), which must stay <= 1
//   headline    m = 128^3 points (a box-shaped grid of about 2.1e6 points), n ~ 2e5,
//               tolerance 0.1, sigma 0.5: total time, per-pass split, error bounds
//   tolerance   tolerance 0.2, 0.1, 0.05 at a medium size
// --only takes a comma-separated list of those names (default: all). --quick runs
// small sizes only (well under a minute). Output: tables on stdout, DIR/descriptors.csv
// and DIR/descriptors.json (default DIR results/bench_descriptors), and DIR/charts.html
// with log-log charts of time against m and against n.
//
// Grids: the part's box grown by PADDING on every side (pipeline/part_fields.h part_grid)
// at the spacing that gives the wanted number of points, then shifted by less than half
// a spacing per axis so that no grid plane lies on one of the part's axis-aligned faces
// (the shift maximizes the smallest distance, reported as face_clearance in spacings).
// Times are wall-clock seconds of compute_descriptors; the kernel programs come from
// the program cache (an untimed run on a 2x2x2 grid of the same mesh and spacing fills it
// with exactly the programs the case needs), so pass times include a cache load, not a
// compile. Short cases are repeated (up to 3 runs or 1 s) and the fastest run is kept.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "core/grid.h"
#include "core/progress.h"
#include "engine/fields/descriptors.h"
#include "engine/runtime/device.h"
#include "mesh/mesh.h"
#include "mesh/procedural/procedural_parts.h"
#include "perf/bench_common.h"
#include "perf/bench_options.h"
#include "pipeline/part_fields.h"
#include "snapfit/error.h"
#include "snapfit/scene.h"

namespace {

using snapfit::DescriptorFields;
using snapfit::DescriptorOptions;
using snapfit::DescriptorParams;
using snapfit::GridSpec;
using snapfit::Mesh;

constexpr double kPadding = 3.0;  // mm on every side of the part's box

// ---------------------------------------------------------------- command line

struct Args : snapfit::bench::CommonArgs {
  std::set<std::string> only;
};

const std::set<std::string> kCases = {"m_sweep", "n_sweep", "brute", "headline", "tolerance"};

Args parse_args(int argc, char** argv) {
  Args a;
  a.out = "results/bench_descriptors";
  a.command_line = snapfit::bench::command_line(argc, argv);
  std::vector<std::string> only;
  CLI::App app{
      "Descriptor fields' cost against grid points m and triangles n, the brute-force reference, a headline "
      "part and the tolerance",
      "bench_descriptors"};
  snapfit::bench::add_common_options(app, a.quick, a.device, a.out,
                                     "small sizes only (a smoke run, well under a minute)");
  app.add_option("--only", only, "comma-separated subset of m_sweep,n_sweep,brute,headline,tolerance")
      ->delimiter(',')
      ->check(CLI::IsMember(kCases));
  snapfit::bench::parse(app, argc, argv);
  a.only.insert(only.begin(), only.end());
  return a;
}

// ---------------------------------------------------------------- parts and grids

snapfit::ProceduralPartSpec base_spec(int segments) {
  // scenes/three_pegs.json, part 1.
  return {"three_peg_base",
          {{"cell", 20}, {"base_thickness", 8}, {"cover_thickness", 6}, {"segments", segments}},
          {{"peg_radii", {3, 4.5, 6}}, {"peg_heights", {8, 10, 12}}, {"fillet_radii", {1, 1.5, 2}}}};
}

class Parts {
 public:
  const Mesh& with_segments(int segments) {
    auto it = meshes_.find(segments);
    if (it == meshes_.end()) it = meshes_.emplace(segments, snapfit::make_procedural_part(base_spec(segments))).first;
    return it->second;
  }
  std::size_t triangles(int segments) { return with_segments(segments).triangles.size(); }
  // The segments (a multiple of 8) whose triangle count is closest to `target`
  // (relative error); counts grow about as segments^2.
  int segments_for(double target) {
    int s = 8 * std::max(1, static_cast<int>(std::lround(64.0 * std::sqrt(target / triangles(64)) / 8.0)));
    auto err = [&](int seg) { return std::abs(std::log(static_cast<double>(triangles(seg)) / target)); };
    for (int step : {8, -8}) {
      while (s + step >= 8 && s + step <= 4096 && err(s + step) < err(s)) s += step;
    }
    return s;
  }

 private:
  std::map<int, Mesh> meshes_;
};

Eigen::AlignedBox3d mesh_box(const Mesh& mesh) {
  Eigen::AlignedBox3d box;
  for (const auto& v : mesh.vertices) box.extend(v);
  return box;
}

// Coordinates of the axis-aligned planes that hold some of the mesh's faces.
std::array<std::vector<double>, 3> axis_planes(const Mesh& mesh) {
  std::array<std::set<double>, 3> planes;
  for (const auto& t : mesh.triangles) {
    const Eigen::Vector3d a = mesh.vertices[t[0]], b = mesh.vertices[t[1]], c = mesh.vertices[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double len = n.norm();
    if (!(len > 0)) continue;
    for (int ax = 0; ax < 3; ++ax)
      if (std::abs(n[ax]) >= len * (1 - 1e-12)) planes[ax].insert(std::round(a[ax] * 1e9) / 1e9);
  }
  std::array<std::vector<double>, 3> out;
  for (int ax = 0; ax < 3; ++ax) out[ax].assign(planes[ax].begin(), planes[ax].end());
  return out;
}

struct Grid {
  GridSpec spec;
  double face_clearance = 0;  // smallest distance of a grid plane to an axis-aligned face, in spacings
};

// Smallest distance (in spacings) from any plane in `planes` to the grid planes origin + k h.
double clearance(const std::vector<double>& planes, double origin, double h) {
  double best = 0.5;
  for (double p : planes) {
    const double f = (p - origin) / h;
    best = std::min(best, std::abs(f - std::round(f)));
  }
  return best;
}

// About `target_points` grid points over the padded box of `mesh`, shifted off its faces.
Grid make_bench_grid(const Mesh& mesh, double target_points) {
  const Eigen::AlignedBox3d box = mesh_box(mesh);
  const Eigen::Vector3d extent = (box.max() - box.min()).array() + 2 * kPadding;
  snapfit::GridParams gp;
  gp.padding = kPadding;
  auto points = [&](double h) { return static_cast<double>(snapfit::part_grid(mesh, gp, h).count()); };
  // Bisection on the spacing (the count decreases with h, in steps).
  double lo = std::cbrt(extent.prod() / target_points) * 0.5, hi = lo * 4;
  double best_h = lo, best_err = std::numeric_limits<double>::infinity();
  for (int it = 0; it < 60; ++it) {
    const double h = 0.5 * (lo + hi);
    const double c = points(h);
    const double err = std::abs(c - target_points);
    if (err < best_err) best_err = err, best_h = h;
    (c > target_points ? lo : hi) = h;
  }
  Grid g;
  g.spec = snapfit::part_grid(mesh, gp, best_h);
  const auto planes = axis_planes(mesh);
  const double h = g.spec.spacing;
  g.face_clearance = 0.5;
  for (int ax = 0; ax < 3; ++ax) {
    // Candidate shifts in [-h/2, h/2): golden-ratio sequence; keep the best clearance.
    double best_shift = 0, best_c = clearance(planes[ax], g.spec.origin[ax], h);
    for (int k = 1; k <= 97; ++k) {
      const double f = std::fmod(k * 0.6180339887498949 + 0.1 * ax, 1.0) - 0.5;
      const double c = clearance(planes[ax], g.spec.origin[ax] + f * h, h);
      if (c > best_c + 1e-9) best_c = c, best_shift = f * h;
    }
    g.spec.origin[ax] += best_shift;
    g.face_clearance = std::min(g.face_clearance, best_c);
  }
  return g;
}

std::string dims_string(const GridSpec& g) {
  return std::to_string(g.dims.x()) + "x" + std::to_string(g.dims.y()) + "x" + std::to_string(g.dims.z());
}

// ---------------------------------------------------------------- measurements

using snapfit::bench::load1;
using snapfit::bench::process_cpu_seconds;

struct Row {
  std::string case_name;
  std::string m_label;  // e.g. "64^3"
  GridSpec grid;
  double face_clearance = 0;
  int segments = 0;
  std::size_t n_triangles = 0;
  std::size_t refined_triangles = 0;
  double tolerance = 0, sigma = 0;
  std::string variant;  // "hierarchical" or "brute_force"
  int lanes = 1;        // grid points per density work item
  double cpu_s = 0;     // process CPU seconds of the kept run (robust to other load)
  double seconds = 0, distance_s = 0, winding_s = 0, density_s = 0, refine_s = 0, bvh_s = 0;
  double max_bound = 0, mean_bound = 0, mean_abs_s = 0, median_bound = 0;
  double max_winding_bound = 0, mean_winding_bound = 0;
  int runs = 1;
  double load_before = 0, load_after = 0;
};

struct Measured {
  Row row;
  DescriptorFields fields;
};

Measured measure(const snapfit::ComputeContext& ctx, const std::string& case_name, const std::string& m_label,
                 const Mesh& mesh, int segments, const Grid& grid, double tolerance, double sigma, bool brute,
                 bool progress, bool quiet_repeat = false) {
  DescriptorParams params;
  params.tolerance = tolerance;
  params.sigma = sigma;
  DescriptorOptions options;
  options.brute_force_density = brute;
  if (progress) options.progress = snapfit::pass_progress_bars(std::cerr);

  // Kernels are compiled with the BVH depth in their flags (STACK_SIZE), which depends on
  // the mesh and, through the refinement, on the spacing: one untimed run on a 2x2x2 grid
  // of the same spacing puts exactly these programs in the program cache first.
  {
    GridSpec tiny = grid.spec;
    tiny.dims = Eigen::Vector3i(2, 2, 2);
    DescriptorOptions warm = options;
    warm.progress = nullptr;
    snapfit::compute_descriptors(ctx, mesh, tiny, params, warm);
  }
  Measured best;
  best.row.load_before = load1();
  double spent = 0;
  int runs = 0;
  // Short cases: up to 3 runs or about 1 s, keeping the fastest.
  while (true) {
    const double cpu0 = process_cpu_seconds();
    DescriptorFields f = snapfit::compute_descriptors(ctx, mesh, grid.spec, params, options);
    const double cpu = process_cpu_seconds() - cpu0;
    ++runs;
    spent += f.seconds;
    if (runs == 1 || f.seconds < best.fields.seconds) best.fields = std::move(f), best.row.cpu_s = cpu;
    if (quiet_repeat || runs >= 3 || spent > 1.0) break;
  }
  const DescriptorFields& f = best.fields;
  Row& r = best.row;
  r.load_after = load1();
  r.runs = runs;
  r.case_name = case_name;
  r.m_label = m_label;
  r.grid = grid.spec;
  r.face_clearance = grid.face_clearance;
  r.segments = segments;
  r.n_triangles = mesh.triangles.size();
  r.refined_triangles = f.refined_triangles;
  r.tolerance = tolerance;
  r.sigma = sigma;
  r.variant = brute ? "brute_force" : "hierarchical";
  r.lanes = f.density_lanes;
  r.seconds = f.seconds;
  r.distance_s = f.distance_seconds;
  r.winding_s = f.winding_seconds;
  r.density_s = f.density_seconds;
  r.refine_s = f.refine_seconds;
  r.bvh_s = f.bvh_seconds;
  double sum_b = 0, sum_s = 0, max_b = 0, sum_wb = 0, max_wb = 0;
  for (std::size_t i = 0; i < f.density_bound.size(); ++i) {
    sum_b += f.density_bound[i];
    max_b = std::max(max_b, static_cast<double>(f.density_bound[i]));
    sum_s += std::abs(f.skeletal_density[i]);
  }
  for (float b : f.winding_bound) sum_wb += b, max_wb = std::max(max_wb, static_cast<double>(b));
  const double count = static_cast<double>(f.winding.size());
  r.max_bound = max_b;
  r.mean_bound = sum_b / count;
  r.mean_abs_s = sum_s / count;
  std::vector<float> sorted = f.density_bound;
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  r.median_bound = sorted.empty() ? 0 : sorted[sorted.size() / 2];
  r.max_winding_bound = max_wb;
  r.mean_winding_bound = sum_wb / count;
  return best;
}

struct BruteComparison {
  std::string m_label;
  std::string dims;
  std::size_t points = 0, n_triangles = 0;
  double hier_total = 0, brute_total = 0, hier_density = 0, brute_density = 0;
  double speedup_density = 0, speedup_total = 0;
  double max_abs_diff = 0;  // max |s_h - s_b|
  double mean_abs_diff = 0, mean_bound_sum = 0;
  double max_diff_over_bounds = 0;  // max |s_h - s_b| / (bound_h + bound_b)
  std::size_t points_over = 0;      // points where |s_h - s_b| > bound_h + bound_b
  double max_bound_sum = 0, mean_abs_s = 0;
};

BruteComparison compare(const Measured& h, const Measured& b) {
  BruteComparison c;
  c.m_label = h.row.m_label;
  c.dims = dims_string(h.row.grid);
  c.points = h.row.grid.count();
  c.n_triangles = h.row.n_triangles;
  c.hier_total = h.row.seconds;
  c.brute_total = b.row.seconds;
  c.hier_density = h.row.density_s;
  c.brute_density = b.row.density_s;
  c.speedup_density = c.brute_density / c.hier_density;
  c.speedup_total = c.brute_total / c.hier_total;
  c.mean_abs_s = h.row.mean_abs_s;
  const auto& sh = h.fields.skeletal_density;
  const auto& sb = b.fields.skeletal_density;
  for (std::size_t i = 0; i < sh.size(); ++i) {
    const double d = std::abs(static_cast<double>(sh[i]) - sb[i]);
    const double bounds = static_cast<double>(h.fields.density_bound[i]) + b.fields.density_bound[i];
    c.max_abs_diff = std::max(c.max_abs_diff, d);
    c.mean_abs_diff += d / sh.size();
    c.mean_bound_sum += bounds / sh.size();
    c.max_bound_sum = std::max(c.max_bound_sum, bounds);
    if (d > bounds) ++c.points_over;
    if (bounds > 0)
      c.max_diff_over_bounds = std::max(c.max_diff_over_bounds, d / bounds);
    else if (d > 0)
      c.max_diff_over_bounds = std::numeric_limits<double>::infinity();
  }
  return c;
}

// ---------------------------------------------------------------- output

using snapfit::bench::fmt;
std::string fixed(double v, int prec = 2) { return snapfit::bench::fixed(v, prec); }

void print_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  std::vector<std::size_t> w(header.size());
  for (std::size_t c = 0; c < header.size(); ++c) w[c] = header[c].size();
  for (const auto& r : rows)
    for (std::size_t c = 0; c < r.size() && c < w.size(); ++c) w[c] = std::max(w[c], r[c].size());
  auto line = [&](const std::vector<std::string>& r) {
    for (std::size_t c = 0; c < header.size(); ++c) {
      const std::string& s = c < r.size() ? r[c] : std::string();
      std::cout << (c ? "  " : "") << (c == 0 ? std::left : std::right) << std::setw(static_cast<int>(w[c])) << s;
    }
    std::cout << std::right << "\n";
  };
  line(header);
  std::vector<std::string> rule;
  for (std::size_t c = 0; c < header.size(); ++c) rule.push_back(std::string(w[c], '-'));
  line(rule);
  for (const auto& r : rows) line(r);
  std::cout << std::flush;
}

void print_rows(const std::string& title, const std::vector<Row>& rows) {
  std::cout << "\n== " << title << "\n";
  std::vector<std::vector<std::string>> t;
  for (const Row& r : rows)
    t.push_back({r.m_label,
                 dims_string(r.grid),
                 std::to_string(r.grid.count()),
                 std::to_string(r.n_triangles),
                 std::to_string(r.refined_triangles),
                 fmt(r.tolerance),
                 r.variant == "brute_force" ? "brute" : "hier",
                 std::to_string(r.lanes),
                 fixed(r.seconds),
                 fixed(r.cpu_s, 1),
                 fixed(r.distance_s),
                 fixed(r.winding_s),
                 fixed(r.density_s),
                 fixed(r.refine_s),
                 fixed(r.bvh_s),
                 fmt(r.max_bound),
                 fmt(r.mean_bound),
                 fmt(r.median_bound),
                 fmt(r.mean_abs_s),
                 fmt(r.mean_bound / r.mean_abs_s),
                 std::to_string(r.runs),
                 fixed(r.load_before, 1)});
  print_table({"m",          "dims",      "points",  "n",       "refined", "tol",      "variant", "lanes",
               "total s",    "cpu s",     "dist s",  "wind s",  "dens s",  "refine s", "bvh s",   "max bound",
               "mean bound", "p50 bound", "mean|s|", "bnd/|s|", "runs",    "load"},
              t);
}

nlohmann::json row_json(const Row& r) {
  return {{"case", r.case_name},
          {"m", r.grid.count()},
          {"m_label", r.m_label},
          {"dims", dims_string(r.grid)},
          {"spacing", r.grid.spacing},
          {"origin", {r.grid.origin.x(), r.grid.origin.y(), r.grid.origin.z()}},
          {"face_clearance_spacings", r.face_clearance},
          {"segments", r.segments},
          {"n_triangles", r.n_triangles},
          {"refined_triangles", r.refined_triangles},
          {"tolerance", r.tolerance},
          {"sigma", r.sigma},
          {"variant", r.variant},
          {"lanes", r.lanes},
          {"seconds", r.seconds},
          {"cpu_s", r.cpu_s},
          {"distance_s", r.distance_s},
          {"winding_s", r.winding_s},
          {"density_s", r.density_s},
          {"refine_s", r.refine_s},
          {"bvh_s", r.bvh_s},
          {"max_bound", r.max_bound},
          {"mean_bound", r.mean_bound},
          {"median_bound", r.median_bound},
          {"mean_abs_s", r.mean_abs_s},
          {"mean_bound_over_mean_abs_s", r.mean_bound / r.mean_abs_s},
          {"max_winding_bound", r.max_winding_bound},
          {"mean_winding_bound", r.mean_winding_bound},
          {"runs", r.runs},
          {"load_before", r.load_before},
          {"load_after", r.load_after}};
}

void write_csv(const std::filesystem::path& path, const std::vector<Row>& rows) {
  snapfit::bench::CsvFile f(
      path,
      "case,m,dims,n_triangles,tolerance,sigma,variant,seconds,distance_s,winding_s,density_s,"
      "refine_s,bvh_s,max_bound,mean_bound,mean_abs_s,m_label,spacing,segments,refined_triangles,"
      "max_winding_bound,mean_winding_bound,runs,load_before,load_after,median_bound,cpu_s,lanes");
  for (const Row& r : rows)
    f.row(r.case_name, r.grid.count(), dims_string(r.grid), r.n_triangles, r.tolerance, r.sigma, r.variant, r.seconds,
          r.distance_s, r.winding_s, r.density_s, r.refine_s, r.bvh_s, r.max_bound, r.mean_bound, r.mean_abs_s,
          r.m_label, r.grid.spacing, r.segments, r.refined_triangles, r.max_winding_bound, r.mean_winding_bound, r.runs,
          r.load_before, r.load_after, r.median_bound, r.cpu_s, r.lanes);
}

// ---------------------------------------------------------------- charts

// Log-log charts of the m sweep and the n sweep from the JSON rows, on DIR/charts.html.
// Returns a line saying what was written.
std::string write_plots(const std::filesystem::path& dir, const nlohmann::json& rows, const std::string& command) {
  struct Pass {
    const char* key;
    const char* label;
  };
  const std::vector<Pass> passes = {{"seconds", "total"},
                                    {"density_s", "skeletal density"},
                                    {"winding_s", "winding number"},
                                    {"distance_s", "distance"},
                                    {"refine_s", "refine + BVH (host)"}};
  auto chart_for = [&](const std::string& case_name, const std::string& x_key, const std::string& title,
                       const std::string& x_label) {
    snapfit::Chart c = snapfit::bench::make_chart(title, x_label, "seconds", true, true);
    for (const Pass& p : passes) {
      snapfit::Series s;
      s.label = p.label;
      for (const auto& r : rows) {
        if (r.value("case", "") != case_name || r.value("variant", "") != "hierarchical") continue;
        s.x.push_back(r.at(x_key).get<double>());
        double y = r.at(p.key).get<double>();
        if (std::string(p.key) == "refine_s") y += r.at("bvh_s").get<double>();
        s.y.push_back(y);
      }
      if (!s.x.empty()) c.series.push_back(std::move(s));
    }
    return c;
  };
  std::vector<snapfit::Chart> charts;
  auto title_value = [&](const std::string& case_name, const char* key) -> std::string {
    for (const auto& r : rows)
      if (r.value("case", "") == case_name)
        return r.at(key).is_string() ? r.at(key).get<std::string>() : r.at(key).dump();
    return "?";
  };
  for (const auto& [case_name, x_key, title, x_label] : std::vector<std::array<std::string, 4>>{
           {"m_sweep", "m",
            "descriptors: time vs grid points m (three_peg_base, n = " + title_value("m_sweep", "n_triangles") + ")",
            "grid points m"},
           {"n_sweep", "n_triangles",
            "descriptors: time vs triangles n (three_peg_base, m = " + title_value("n_sweep", "dims") + ")",
            "triangles n"}}) {
    snapfit::Chart c = chart_for(case_name, x_key, title, x_label);
    if (!c.series.empty()) charts.push_back(std::move(c));
  }
  if (charts.empty()) return "plots: none (no m or n sweep in this run)";
  return "plots: " + snapfit::bench::write_charts(dir, "bench_descriptors: time against m and n", command, charts);
}

// ---------------------------------------------------------------- the run

// What every case needs: the command line, the device and the part at its resolutions.
struct Cases {
  const Args& args;
  const snapfit::ComputeContext& ctx;
  Parts& parts;
};

constexpr double kSigma = 0.5;
const double kDefaultTolerance = DescriptorParams{}.tolerance;  // the descriptors' own

std::string label(int side) { return std::to_string(side) + "^3"; }
Grid grid_for(const Mesh& mesh, int side) { return make_bench_grid(mesh, std::pow(side, 3.0)); }
// Progress bars for cases expected to take more than a few seconds.
bool long_case(const Args& args, std::size_t points, std::size_t n) { return !args.quick && points * 1.0 * n > 5e10; }

// a. time against m at fixed n.
void m_sweep(Cases& c, std::vector<Row>& rows) {
  std::vector<Row> m_rows;
  const double n_target = c.args.quick ? 2e3 : 1e4;
  const std::vector<int> sides = c.args.quick ? std::vector<int>{12, 16, 24} : std::vector<int>{32, 48, 64, 96, 128};
  const int seg = c.parts.segments_for(n_target);
  const Mesh& mesh = c.parts.with_segments(seg);
  for (int side : sides) {
    const Grid g = grid_for(mesh, side);
    std::cerr << "m_sweep: " << label(side) << " (" << dims_string(g.spec) << "), n " << mesh.triangles.size() << "\n";
    m_rows.push_back(measure(c.ctx, "m_sweep", label(side), mesh, seg, g, kDefaultTolerance, kSigma, false,
                             long_case(c.args, g.spec.count(), mesh.triangles.size()))
                         .row);
  }
  print_rows("a. time against grid points m (n = " + std::to_string(mesh.triangles.size()) + " triangles, tolerance " +
                 fmt(kDefaultTolerance) + ", sigma 0.5)",
             m_rows);
  rows.insert(rows.end(), m_rows.begin(), m_rows.end());
}

// b. time against n at fixed m.
void n_sweep(Cases& c, std::vector<Row>& rows) {
  std::vector<Row> n_rows;
  const int side = c.args.quick ? 16 : 64;
  const std::vector<double> targets =
      c.args.quick ? std::vector<double>{1e3, 5e3} : std::vector<double>{1e3, 1e4, 5e4, 2e5};
  for (double target : targets) {
    const int seg = c.parts.segments_for(target);
    const Mesh& mesh = c.parts.with_segments(seg);
    const Grid g = grid_for(mesh, side);
    std::cerr << "n_sweep: n " << mesh.triangles.size() << " (segments " << seg << "), " << dims_string(g.spec) << "\n";
    n_rows.push_back(measure(c.ctx, "n_sweep", label(side), mesh, seg, g, kDefaultTolerance, kSigma, false,
                             long_case(c.args, g.spec.count(), mesh.triangles.size()))
                         .row);
  }
  print_rows(
      "b. time against triangle count n (m = " + label(side) + ", tolerance " + fmt(kDefaultTolerance) + ", sigma 0.5)",
      n_rows);
  rows.insert(rows.end(), n_rows.begin(), n_rows.end());
}

// c. brute force against the hierarchy.
void brute_force(Cases& c, std::vector<Row>& rows, std::vector<BruteComparison>& comparisons) {
  struct Size {
    int side;
    double n;
  };
  const std::vector<Size> sizes =
      c.args.quick ? std::vector<Size>{{12, 1e3}} : std::vector<Size>{{24, 2e3}, {24, 1e4}, {32, 2e3}};
  std::vector<Row> b_rows;
  for (const Size& s : sizes) {
    const int seg = c.parts.segments_for(s.n);
    const Mesh& mesh = c.parts.with_segments(seg);
    const Grid g = grid_for(mesh, s.side);
    std::cerr << "brute: " << label(s.side) << " (" << dims_string(g.spec) << "), n " << mesh.triangles.size() << "\n";
    const Measured h =
        measure(c.ctx, "brute_vs_hier", label(s.side), mesh, seg, g, kDefaultTolerance, kSigma, false, false);
    const Measured b = measure(c.ctx, "brute_vs_hier", label(s.side), mesh, seg, g, kDefaultTolerance, kSigma, true,
                               !c.args.quick, true);
    comparisons.push_back(compare(h, b));
    b_rows.push_back(h.row);
    b_rows.push_back(b.row);
  }
  print_rows("c. brute-force density (the paper's O(mn) sum) against the hierarchy", b_rows);
  std::cout << "\n";
  std::vector<std::vector<std::string>> t;
  for (const auto& c : comparisons)
    t.push_back({c.m_label, c.dims, std::to_string(c.n_triangles), fixed(c.hier_density, 3), fixed(c.brute_density, 3),
                 fixed(c.speedup_density, 1) + "x", fixed(c.hier_total, 3), fixed(c.brute_total, 3),
                 fixed(c.speedup_total, 1) + "x", fmt(c.max_abs_diff), fmt(c.mean_abs_diff), fmt(c.max_bound_sum),
                 fmt(c.mean_bound_sum), fmt(c.max_diff_over_bounds), std::to_string(c.points_over), fmt(c.mean_abs_s)});
  print_table(
      {"m", "dims", "n", "hier dens s", "brute dens s", "speed-up", "hier total", "brute total", "speed-up",
       "max|s_h-s_b|", "mean|s_h-s_b|", "max(b_h+b_b)", "mean(b_h+b_b)", "max|diff|/(b_h+b_b)", "pts over", "mean|s|"},
      t);
  rows.insert(rows.end(), b_rows.begin(), b_rows.end());
}

// d. the headline; returns its row as JSON.
nlohmann::json headline(Cases& c, std::vector<Row>& rows) {
  const int side = c.args.quick ? 24 : 128;
  const double n_target = c.args.quick ? 1e4 : 2e5;
  const int seg = c.parts.segments_for(n_target);
  const Mesh& mesh = c.parts.with_segments(seg);
  const Grid g = grid_for(mesh, side);
  std::cerr << "headline: " << label(side) << " (" << dims_string(g.spec) << " = " << g.spec.count()
            << " points, spacing " << g.spec.spacing << " mm), n " << mesh.triangles.size() << " (segments " << seg
            << "), tolerance " << kDefaultTolerance << ", sigma " << kSigma << "\n";
  const Measured m =
      measure(c.ctx, "headline", label(side), mesh, seg, g, kDefaultTolerance, kSigma, false, !c.args.quick, true);
  const Row& r = m.row;
  print_rows("d. headline: m = " + label(side) + " points, n ~ " + fmt(n_target) + " triangles", {r});
  std::cout << "   grid " << dims_string(r.grid) << " = " << r.grid.count() << " points, spacing "
            << fmt(r.grid.spacing, 4) << " mm, faces >= " << fixed(r.face_clearance, 2)
            << " spacings from grid planes\n"
            << "   total " << fixed(r.seconds) << " s = bvh " << fixed(r.bvh_s) << " + refine " << fixed(r.refine_s)
            << " (" << r.refined_triangles << " triangles) + distance " << fixed(r.distance_s) << " + winding "
            << fixed(r.winding_s) << " + density " << fixed(r.density_s) << " s (rest "
            << fixed(r.seconds - r.bvh_s - r.refine_s - r.distance_s - r.winding_s - r.density_s) << " s)\n"
            << "   process CPU " << fixed(r.cpu_s, 1) << " s (" << fixed(r.cpu_s / r.seconds, 2)
            << " cores busy on average; on an idle machine with all " << c.ctx.device.info.compute_units
            << " compute units, about " << fixed(r.cpu_s / std::max(1u, c.ctx.device.info.compute_units), 1) << " s)\n"
            << "   density bound: max " << fmt(r.max_bound) << ", mean " << fmt(r.mean_bound) << ", median "
            << fmt(r.median_bound) << "; mean |s| " << fmt(r.mean_abs_s) << "; mean bound / mean |s| "
            << fmt(r.mean_bound / r.mean_abs_s) << "\n"
            << "   winding bound: max " << fmt(r.max_winding_bound) << ", mean " << fmt(r.mean_winding_bound) << "\n";
  if (!c.args.quick)
    std::cout << "   target (m = 128^3, n = 2e5 in <= 60 s): " << (r.seconds <= 60 ? "met" : "NOT met") << " ("
              << fixed(r.seconds, 1) << " s, load " << fixed(r.load_before, 1) << " -> " << fixed(r.load_after, 1)
              << ")\n";
  rows.push_back(r);
  return row_json(r);
}

// e. tolerance sweep.
void tolerance_sweep(Cases& c, std::vector<Row>& rows) {
  const int side = c.args.quick ? 16 : 48;
  const double n_target = c.args.quick ? 2e3 : 5e4;
  const int seg = c.parts.segments_for(n_target);
  const Mesh& mesh = c.parts.with_segments(seg);
  const Grid g = grid_for(mesh, side);
  std::vector<Row> t_rows;
  for (double tol : {0.2, 0.1, 0.05}) {
    std::cerr << "tolerance: " << tol << ", " << dims_string(g.spec) << ", n " << mesh.triangles.size() << "\n";
    t_rows.push_back(measure(c.ctx, "tolerance", label(side), mesh, seg, g, tol, kSigma, false, false).row);
  }
  print_rows("e. tolerance sweep (m = " + label(side) + ", n = " + std::to_string(mesh.triangles.size()) + ")", t_rows);
  rows.insert(rows.end(), t_rows.begin(), t_rows.end());
}

// Fills the program cache for every kernel and both density variants.
void warm_up(const snapfit::ComputeContext& ctx, Parts& parts) {
  const auto t = std::chrono::steady_clock::now();
  const Mesh& m = parts.with_segments(8);
  const Grid g = make_bench_grid(m, 6 * 6 * 6);
  DescriptorParams p;
  DescriptorOptions o;
  snapfit::compute_descriptors(ctx, m, g.spec, p, o);
  o.brute_force_density = true;
  snapfit::compute_descriptors(ctx, m, g.spec, p, o);
  std::cout << "warm-up (program build or cache load, both variants): "
            << fixed(std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count()) << " s\n";
}

nlohmann::json comparison_json(const BruteComparison& c) {
  return {{"m_label", c.m_label},
          {"dims", c.dims},
          {"m", c.points},
          {"n_triangles", c.n_triangles},
          {"hierarchical_density_s", c.hier_density},
          {"brute_force_density_s", c.brute_density},
          {"speedup_density", c.speedup_density},
          {"hierarchical_total_s", c.hier_total},
          {"brute_force_total_s", c.brute_total},
          {"speedup_total", c.speedup_total},
          {"max_abs_difference", c.max_abs_diff},
          {"mean_abs_difference", c.mean_abs_diff},
          {"mean_bound_sum", c.mean_bound_sum},
          {"max_bound_sum", c.max_bound_sum},
          {"max_difference_over_bound_sum", c.max_diff_over_bounds},
          {"points_over_bound_sum", c.points_over},
          {"mean_abs_s", c.mean_abs_s}};
}

int run(const Args& args) {
  const auto wall_start = std::chrono::steady_clock::now();
  const snapfit::Device device = snapfit::select_device(snapfit::device_spec_from(args.device));
  const snapfit::ComputeContext ctx = snapfit::make_compute_context(device);
  const auto& info = device.info;
  const double load_start = load1();
  std::cout << "bench_descriptors" << (args.quick ? " (quick)" : "") << "\n"
            << "device: " << snapfit::describe_device(info) << "\n"
            << "driver: " << info.driver_version << ", " << info.platform_version << ", " << info.compute_units
            << " compute units; host threads " << std::thread::hardware_concurrency() << "\n"
            << "load average at start: " << fixed(load_start) << " (shared machine: other work may be running)\n";

  Parts parts;
  auto want = [&](const std::string& c) { return args.only.empty() || args.only.count(c) > 0; };
  const int seg64 = 64;
  std::cout << "part: three_peg_base of scenes/three_pegs.json (radii 3/4.5/6 mm, fillets 1/1.5/2 mm, heights "
               "8/10/12 mm, cell 20 mm, base 8 mm); box "
            << (mesh_box(parts.with_segments(seg64)).sizes().transpose()) << " mm, padding " << kPadding
            << " mm; segments 64 gives " << parts.triangles(seg64) << " triangles\n";

  warm_up(ctx, parts);

  Cases cases{args, ctx, parts};
  std::vector<Row> rows;
  std::vector<BruteComparison> comparisons;
  nlohmann::json headline_json;
  if (want("m_sweep")) m_sweep(cases, rows);
  if (want("n_sweep")) n_sweep(cases, rows);
  if (want("brute")) brute_force(cases, rows, comparisons);
  if (want("headline")) headline_json = headline(cases, rows);
  if (want("tolerance")) tolerance_sweep(cases, rows);

  // Files.
  const std::filesystem::path dir(args.out);
  std::filesystem::create_directories(dir);
  write_csv(dir / "descriptors.csv", rows);
  nlohmann::json j;
  j["benchmark"] = "bench_descriptors";
  j["command_line"] = args.command_line;
  j["date"] = snapfit::bench::now_iso();
  j["quick"] = args.quick;
  j["device"] = snapfit::bench::device_record(info);
  j["host"] = {{"hardware_threads", std::thread::hardware_concurrency()},
               {"load_average_start", load_start},
               {"load_average_end", load1()}};
  j["part"] = {{"type", "three_peg_base"},
               {"parameters", "scenes/three_pegs.json part1, segments varied"},
               {"padding_mm", kPadding}};
  j["rows"] = nlohmann::json::array();
  for (const Row& r : rows) j["rows"].push_back(row_json(r));
  j["brute_force_comparison"] = nlohmann::json::array();
  for (const auto& c : comparisons) j["brute_force_comparison"].push_back(comparison_json(c));
  if (!headline_json.is_null()) j["headline"] = headline_json;
  j["wall_seconds"] = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  snapfit::bench::write_json(dir / "descriptors.json", j);
  std::cout << "\nwrote " << (dir / "descriptors.csv").string() << " and " << (dir / "descriptors.json").string()
            << " (" << fixed(j["wall_seconds"].get<double>(), 1) << " s in all; load average " << fixed(load_start)
            << " -> " << fixed(load1()) << ")\n"
            << write_plots(dir, j["rows"], j.value("command_line", std::string("bench_descriptors"))) << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return snapfit::bench::guarded_main("bench_descriptors", [&] { return run(parse_args(argc, argv)); });
}
