// `snapfit spheres SCENE`: a part's spherical decomposition (seed 001 Algorithm 1) at one
// or more tolerances, with its error against the solid, and an export of the balls for
// ParaView.
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "snapfit/error.h"
#include "snapfit/export.h"
#include "snapfit/spheres.h"

namespace snapfit::cli {
namespace {

struct SpheresOptions {
  std::string scene;
  std::string part = "1";
  std::vector<double> tolerances;
  double protrusion = 0.25;
  std::string order = "sdf";
  std::size_t samples = 200000;
  std::string vtp;
  std::string device;
  bool json = false;
};

nlohmann::json decomposition_json(int part, const SphereDecomposition& d, const BallUnionError& e) {
  return {{"part", part},
          {"tolerance", d.epsilon},
          {"balls", d.balls.size()},
          {"sampled_balls", d.sampled_balls},
          {"grid_nodes", d.grid_nodes},
          {"inside_nodes", d.inside_nodes},
          {"spacing", d.spacing},
          {"hausdorff_bound", d.epsilon},
          {"hausdorff_sampled", e.hausdorff_sampled},
          {"volume_error", e.volume_error},
          {"volume_error_ci95", {e.volume_error_low, e.volume_error_high}},
          {"relative_volume_error", e.volume_error / e.solid_volume},
          {"solid_volume", e.solid_volume},
          {"samples", e.samples},
          {"seconds", d.seconds},
          {"field_seconds", d.field_seconds},
          {"error_seconds", e.seconds}};
}

void print_level(const SpheresOptions& opt, const Scene& scene, int which, const SpheresAtTolerance& level) {
  const SphereDecomposition& d = level.decomposition;
  const BallUnionError& e = level.error;
  if (opt.json) {
    std::cout << decomposition_json(which, d, e).dump() << std::endl;
    return;
  }
  std::cout << "part " << which << " at tolerance " << level.tolerance << " " << scene.units << ": " << d.balls.size()
            << " balls (" << d.sampled_balls << " before reduction) from " << d.inside_nodes << " of " << d.grid_nodes
            << " grid nodes; volume error " << e.volume_error << " " << scene.units << "^3 (95% [" << e.volume_error_low
            << ", " << e.volume_error_high << "], " << 100.0 * e.volume_error / e.solid_volume
            << "% of the solid); Hausdorff <= " << d.epsilon << " (sampled " << e.hausdorff_sampled << "); "
            << d.seconds << " s" << std::endl;
}

// One piece per tolerance: the balls' centres with their radius and the tolerance.
PointPiece ball_piece(const SpheresAtTolerance& level) {
  PointPiece piece;
  PointScalars radius{"radius", {}}, tol{"tolerance", {}};
  for (const Ball& b : level.decomposition.balls) {
    piece.points.push_back(b.centre);
    radius.values.push_back(b.radius);
    tol.values.push_back(level.tolerance);
  }
  piece.scalars = {radius, tol};
  return piece;
}

void run_spheres(const SpheresOptions& opt) {
  if (opt.part != "1" && opt.part != "2") throw Error("--part: expected 1 or 2 (got '" + opt.part + "')");
  if (opt.order != "sdf" && opt.order != "distance")
    throw Error("--order: expected sdf or distance (got '" + opt.order + "')");
  if (opt.samples == 0) throw Error("--samples: must be at least 1");
  const Scene scene = load_scene(opt.scene);
  PartSpheresRequest request;
  request.part = opt.part == "1" ? 1 : 2;
  request.tolerances = opt.tolerances;
  request.protrusion = opt.protrusion;
  request.order = opt.order == "sdf" ? BallOrder::skeletal_density : BallOrder::distance;
  request.samples = opt.samples;
  request.device = opt.device;
  request.progress = true;
  const PartSpheres spheres = decompose_part_spheres(
      scene, request, [&](const SpheresAtTolerance& level) { print_level(opt, scene, request.part, level); });
  if (!opt.vtp.empty()) {
    std::vector<PointPiece> pieces;
    for (const SpheresAtTolerance& level : spheres.levels) pieces.push_back(ball_piece(level));
    write_points_vtp(opt.vtp, pieces);
    if (!opt.json) std::cout << "wrote " << opt.vtp << " (one piece per tolerance; point data radius, tolerance)\n";
  }
}

}  // namespace

void add_spheres_command(CLI::App& app) {
  auto opt = std::make_shared<SpheresOptions>();
  CLI::App* cmd = app.add_subcommand(
      "spheres", "A part's spherical decomposition (seed 001 Algorithm 1) and its error against the solid");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option("--part", opt->part, "Which part: 1 (fixed) or 2 (moving)");
  cmd->add_option("--tolerance", opt->tolerances,
                  "Hausdorff bound epsilon in scene units (repeatable; default the scene's grid spacing); the "
                  "decomposition grid has spacing 2 epsilon / sqrt(3)")
      ->take_all();
  cmd->add_option("--protrusion", opt->protrusion, "Protrusion factor mu of seed 001 (A.1), in [0, 1]")
      ->check(CLI::Range(0.0, 1.0));
  cmd->add_option("--order", opt->order, "Greedy order: sdf (skeletal density, seed 001) or distance");
  cmd->add_option("--samples", opt->samples, "Uniform samples for the volume and Hausdorff error");
  cmd->add_option("--vtp", opt->vtp, "Write the balls as VTK PolyData (points, radius, tolerance) for ParaView");
  cmd->add_option("--device", opt->device, "OpenCL device (see `snapfit devices`)");
  cmd->add_flag("--json", opt->json, "One JSON line per tolerance");
  cmd->callback([opt] { run_spheres(*opt); });
}

}  // namespace snapfit::cli
