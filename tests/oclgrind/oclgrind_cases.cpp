#include "tests/oclgrind/oclgrind_cases.h"

#include <Eigen/Geometry>

#include "engine/query/query_engine.h"
#include "mesh/procedural/procedural_parts.h"
#include "pipeline/part_fields.h"
#include "tests/test_engine_support.h"
#include "tests/test_support.h"

namespace snapfit::test {
namespace {

Mesh procedural(const std::string& type, std::map<std::string, double> numbers) {
  ProceduralPartSpec spec;
  spec.type = type;
  spec.numbers = std::move(numbers);
  return make_procedural_part(spec);
}

GridSpec grid_at(const Mesh& mesh, double spacing) {
  GridParams params;
  params.padding = spacing;
  return part_grid(mesh, params, spacing);
}

DescriptorOptions options(int lanes, std::size_t work_group, std::size_t chunk, bool propagate = true) {
  DescriptorOptions o;
  o.program_cache = test_program_cache();
  o.density_lanes = lanes;
  o.work_group_size = work_group;
  o.chunk_points = chunk;
  o.winding_sign_propagation = propagate;
  return o;
}

// Points of part 1's box and around it, off the grid (explicit coordinates).
std::vector<Eigen::Vector3d> scattered_points(const GridSpec& grid, std::size_t count) {
  std::vector<Eigen::Vector3d> points;
  const Eigen::Vector3d extent = grid.spacing * (grid.dims.cast<double>().array() - 1.0).matrix();
  for (std::size_t i = 0; i < count; ++i) {
    // A low-discrepancy walk (golden-ratio steps) through the grid's box.
    const double a = std::fmod(0.5 + 0.6180339887 * double(i), 1.0), b = std::fmod(0.5 + 0.7548776662 * double(i), 1.0),
                 c = std::fmod(0.5 + 0.5698402910 * double(i), 1.0);
    points.push_back(grid.origin + Eigen::Vector3d(a * extent.x(), b * extent.y(), c * extent.z()));
  }
  return points;
}

}  // namespace

const SmallPair& small_pair() {
  static const SmallPair pair = [] {
    SmallPair p;
    p.part1 = procedural("hole_block", {{"peg_radius", 0.6},
                                        {"clearance", 0.1},
                                        {"hole_depth", 1.2},
                                        {"width", 2.4},
                                        {"height", 1.6},
                                        {"segments", 8}});
    p.part2 = procedural("peg", {{"radius", 0.6}, {"length", 2.0}, {"segments", 8}});
    p.params.kind = DescriptorKind::skeletal_density;
    p.params.sigma = 0.5;
    p.params.tolerance = 0.1;
    p.grid1 = grid_at(p.part1, 0.6);
    p.grid2 = grid_at(p.part2, 0.6);
    p.coarse1 = grid_at(p.part1, 0.8);
    p.coarse2 = grid_at(p.part2, 0.8);
    return p;
  }();
  return pair;
}

std::vector<DescriptorCase> descriptor_cases() {
  const SmallPair& pair = small_pair();
  DescriptorParams indicator = pair.params;
  indicator.kind = DescriptorKind::indicator;
  const std::vector<std::string> all = {"unsigned_distance", "winding_number", "skeletal_density"};
  std::vector<DescriptorCase> cases = {
      {"one point per work-item (a GPU's packet), winding at one seed per component, the runtime's work-groups",
       pair.params, options(1, 0, 16384), false, false, all},
      {"4-point packets, winding at every point, work-groups of 64 (global sizes padded), chunks of 50 points",
       pair.params, options(4, 64, 50, false), false, false, all},
      {"8-point packets (a CPU's), work-groups of 256, chunks of 96 points", pair.params, options(8, 256, 96), false,
       false, all},
      {"16-point packets, work-groups of 32", pair.params, options(16, 32, 16384), false, false, all},
      {"indicator (winding number alone), winding at every point",
       indicator,
       options(0, 0, 16384, false),
       false,
       false,
       {"winding_number"}},
  };
  DescriptorOptions brute = options(1, 0, 16384);
  brute.brute_force_density = true;
  cases.push_back({"brute-force density (every triangle, no hierarchy), part 2", pair.params, brute, true, false, all});
  for (int lanes : {1, 4, 8, 16})
    cases.push_back({"explicit points, " + std::to_string(lanes) + "-point packets", pair.params,
                     options(lanes, lanes == 4 ? 64 : 0, 24), false, true, all});
  return cases;
}

DescriptorFields run_descriptor_case(const ComputeContext& ctx, const DescriptorCase& c) {
  const SmallPair& pair = small_pair();
  const Mesh& mesh = c.part2 ? pair.part2 : pair.part1;
  const GridSpec& grid = c.part2 ? pair.coarse2 : pair.coarse1;
  if (!c.at_points) return compute_descriptors(ctx, mesh, grid, c.params, c.options);
  return descriptors_at_points(ctx, mesh, scattered_points(grid, 45), grid.origin, grid.spacing, c.params, c.options);
}

const std::pair<DescriptorFields, DescriptorFields>& pocl_pair_fields() {
  static const std::pair<DescriptorFields, DescriptorFields> fields = [] {
    const SmallPair& pair = small_pair();
    DescriptorOptions o;
    o.program_cache = test_program_cache();
    return std::make_pair(compute_descriptors(test_context(), pair.part1, pair.grid1, pair.params, o),
                          compute_descriptors(test_context(), pair.part2, pair.grid2, pair.params, o));
  }();
  return fields;
}

const PairSpectra& pocl_pair_spectra() {
  static const PairSpectra spectra = [] {
    const FftLibrary library;
    return compute_pair_spectra(library, test_context(), pocl_pair_fields().first, pocl_pair_fields().second);
  }();
  return spectra;
}

std::vector<Pose> contact_poses(bool translation_only) {
  std::vector<Pose> poses(4);
  for (int i = 0; i < 4; ++i) {
    poses[i].translation = Eigen::Vector3d(0.05 * i, 0.02, -0.5 - 0.1 * i);
    if (!translation_only)
      poses[i].rotation = Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * i, Eigen::Vector3d(1, 2, 3).normalized()));
  }
  return poses;
}

std::vector<QueryCase> query_cases() {
  std::vector<QueryCase> cases;
  for (const Interpolation interpolation : {Interpolation::trilinear, Interpolation::tricubic})
    for (const bool torque : {true, false})
      for (const bool fold : {true, false}) {
        QueryVariant v;
        v.interpolation = interpolation;
        v.torque = torque;
        v.fold_conjugate_pairs = fold;
        cases.push_back({std::string("6-DOF ") + (interpolation == Interpolation::tricubic ? "tricubic" : "trilinear") +
                             (torque ? ", force and torque" : ", force") + (fold ? ", pairs folded" : ", every mode"),
                         v,
                         400,
                         {"pose_query"}});
      }
  QueryVariant half;
  half.interpolation = Interpolation::tricubic;
  half.half_cube = true;
  cases.push_back({"6-DOF tricubic, half-float cube", half, 400, {"pose_query"}});
  QueryVariant energy;
  energy.force = energy.torque = false;
  cases.push_back({"6-DOF trilinear, energy only", energy, 400, {"pose_query"}});
  for (const bool force : {true, false})
    for (const bool fold : {true, false}) {
      QueryVariant v;
      v.translation_only = true;
      v.torque = false;
      v.force = force;
      v.fold_conjugate_pairs = fold;
      cases.push_back({std::string("translation-only lines") + (force ? ", force" : ", energy only") +
                           (fold ? ", pairs folded" : ", every mode"),
                       v,
                       600,
                       {"translation_lines"}});
    }
  for (const bool fold : {true, false}) {
    QueryVariant v;
    v.rotation = RotationMethod::exact_product;
    v.product_update = ProductUpdate::each_query;
    v.product_modes = 300;
    v.fold_conjugate_pairs = fold;
    cases.push_back({std::string("exact rotation: product and its lines") + (fold ? ", pairs folded" : ", every mode"),
                     v,
                     300,
                     {"rotated_product", "rotated_lines"}});
  }
  return cases;
}

std::vector<LaunchShape> query_launch_shapes() {
  return {
      {"the device's own shape", {}},
      // A GPU: 64 work-items per group (the engine's choice everywhere) and up to 2 groups
      // per compute unit per pose, so a handful of modes per group at this m'.
      {"a GPU's: 80 compute units' groups per pose, 16 units of work per group",
       {{"SNAPFIT_QUERY_GROUPS", "160"}, {"SNAPFIT_QUERY_MODES_PER_GROUP", "16"}}},
      {"256 work-items per group (most items idle), 3 groups per pose",
       {{"SNAPFIT_QUERY_WG", "256"}, {"SNAPFIT_QUERY_GROUPS", "3"}, {"SNAPFIT_QUERY_MODES_PER_GROUP", "8"}}},
      {"1 work-item per group", {{"SNAPFIT_QUERY_WG", "1"}, {"SNAPFIT_QUERY_GROUPS", "4"}}},
  };
}

std::vector<QueryResult> run_query_case(const ComputeContext& ctx, const PairSpectra& spectra, const QueryCase& c,
                                        const LaunchShape& shape) {
  std::vector<std::unique_ptr<EnvScope>> env;
  for (const auto& [name, value] : shape.env) env.push_back(std::make_unique<EnvScope>(name, value.c_str()));
  const std::unique_ptr<QueryEngine> engine = make_query_engine(ctx, spectra, c.variant, test_program_cache());
  engine->set_modes(c.modes);
  const std::vector<Pose> poses = contact_poses(c.variant.translation_only);
  std::vector<QueryResult> results = engine->query_batch(poses);
  results.push_back(engine->query(poses[1]));
  return results;
}

}  // namespace snapfit::test
