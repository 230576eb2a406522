// `snapfit search SCENE`: where part 2 fits part 1 over all rotations (snapfit::search,
// snapfit/search.h): one full translational energy map per rotation of a uniform SO(3)
// grid, the best poses of all maps merged, each refined by a local 6-DOF descent. Under
// mpirun the ranks share the rotations cyclically, each on its own OpenCL device
// (cli/search_ranks.h); rank 0 prints the poses and writes the folder.
#include <iostream>
#include <optional>
#include <sstream>

#include "cli/cli_terms.h"
#include "cli/commands.h"
#include "cli/parse_options.h"
#include "cli/search_ranks.h"
#include "report/search_report.h"
#include "snapfit/error.h"
#include "snapfit/search.h"

namespace snapfit::cli {
namespace {

struct SearchOptions {
  std::string scene;
  std::optional<double> step_deg;  // default 30 degrees
  std::optional<std::size_t> rotations;
  std::size_t top = 10;
  std::size_t per_rotation = 4;
  std::string out;
  std::string devices;  // SPEC[;SPEC...]: rank r on entry (node-local rank mod count)
  std::string interpolation = "trilinear";
  std::size_t modes = 0;
  std::size_t refine_modes = 65536;
  std::size_t refine_queries = 200;
  std::string map_fft = "auto";  // auto: measured per (device, size)
  std::size_t map_batch = 0;     // rotations per batch; 0: the measured pick with auto, else 1
};

std::vector<std::string> device_list(const std::string& list) {
  std::vector<std::string> specs;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ';')) specs.push_back(item);
  return specs;
}

void print_plan(const SearchPlan& plan, const std::string& interpolation, const std::string& units) {
  const auto& d = plan.map_dims;
  std::cout << "SO(3) grid: " << plan.rotations << " rotations (" << plan.base_cells << " directions x "
            << plan.psi_steps << " turns, step " << plan.step_deg << " deg), covering radius "
            << plan.covering_radius_deg << " deg\n"
            << "maps: " << d[0] << " x " << d[1] << " x " << d[2] << " translations, spacing " << plan.spacing << " "
            << units << ", " << interpolation << ", " << plan.processes << (plan.processes == 1 ? " rank" : " ranks")
            << "\n"
            << "map FFT: " << in_cli_terms(plan.map_fft) << "\n"
            << "map minima: "
            << (plan.minima_on_device ? "on the device, a short list read back per map"
                                      : "on the host, in each map read back")
            << "\n";
}

void run_search(const SearchOptions& opt, SearchRanks& ranks) {
  if (opt.step_deg && opt.rotations) throw Error("--step-deg and --rotations: give one of them");
  if (!opt.out.empty() && ranks.rank() == 0) check_output_folder(opt.out);
  SearchRequest request;
  request.step_deg = opt.step_deg;
  request.rotations = opt.rotations;
  request.top = opt.top;
  request.per_rotation = opt.per_rotation;
  request.devices = device_list(opt.devices);
  request.interpolation = parse_interpolation(opt.interpolation);
  request.modes = opt.modes;
  request.refine_modes = opt.refine_modes;
  request.refine_queries = opt.refine_queries;
  request.map_fft = opt.map_fft;
  request.map_batch = opt.map_batch;
  request.progress = true;
  // Every rank reads the scene; a rank that cannot ends them all with its message.
  Scene scene;
  std::string error;
  try {
    scene = load_scene(opt.scene);
  } catch (const std::exception& e) {
    error = e.what();
  }
  ranks.checkpoint(error);
  request.on_plan = [&](const SearchPlan& plan) { print_plan(plan, opt.interpolation, scene.units); };
  const SearchResult result = search(scene, request, ranks);
  if (!ranks.root()) return;
  for (std::size_t r = 0; r < result.process_rotations.size(); ++r)
    std::cout << "rank " << r << ": " << result.process_rotations[r] << " rotations in " << result.process_seconds[r]
              << " s (" << double(result.process_rotations[r]) / result.process_seconds[r] << " rotations/s)\n";
  const std::string lines = search_lines(result);
  std::cout << lines;
  if (!opt.out.empty()) {
    write_search_report(opt.out, result, lines, scene.name);
    std::cerr << "wrote " << opt.out << "/top.jsonl, best_per_rotation.csv and search.html\n";
  }
}

}  // namespace

void add_search_command(CLI::App& app) {
  auto opt = std::make_shared<SearchOptions>();
  CLI::App* cmd = app.add_subcommand("search", "Where part 2 fits part 1 over all rotations (one FFT map each; MPI)");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option("--step-deg", opt->step_deg, "Spacing of the SO(3) grid in degrees (default 30)")
      ->check(positive_number());
  cmd->add_option("--rotations", opt->rotations, "About this many rotations instead of --step-deg")
      ->check(positive_number());
  cmd->add_option("--top", opt->top, "Poses to report (default 10)")->check(positive_number());
  cmd->add_option("--per-rotation", opt->per_rotation, "Best minima kept per map (default 4)")
      ->check(positive_number());
  cmd->add_option("--out", opt->out, "Folder for best_per_rotation.csv, search.html and top.jsonl");
  cmd->add_option("--device", opt->devices,
                  "OpenCL device (see `snapfit devices`); SPEC;SPEC;... gives node-local rank r entry r mod count");
  cmd->add_option("--interpolation", opt->interpolation, "Rotated spectrum in the maps: trilinear or tricubic");
  cmd->add_option("--modes", opt->modes, "Low-pass: keep about this many modes in the maps (default: all)");
  cmd->add_option("--refine-modes", opt->refine_modes, "Modes of the refining queries (default 65536)")
      ->check(positive_number());
  cmd->add_option("--refine-queries", opt->refine_queries, "Queries per refined pose at most (default 200)");
  std::string built;
  for (const std::string& name : map_ffts_in_this_build()) built += ", " + name;
  cmd->add_option("--map-fft", opt->map_fft,
                  "Inverse FFT of the maps: auto (the fastest, measured once per device and size)" + built +
                      " (those this build has)");
  cmd->add_option("--map-batch", opt->map_batch,
                  "Rotations mapped per batch on a device FFT (default: measured with --map-fft auto, else 1)")
      ->check(positive_number());
  cmd->callback([opt] {
    SearchRanks ranks;
    try {
      run_search(*opt, ranks);
    } catch (const OtherRankFailed&) {
      throw CLI::RuntimeError(1);  // rank 0 says which rank failed
    } catch (const std::exception& e) {
      if (ranks.size() > 1 && !ranks.root()) {
        // A failure after the last checkpoint (rank 0's refinement cannot fail here).
        std::cerr << "snapfit: error on rank " << ranks.rank() << ": " << e.what() << "\n";
        throw CLI::RuntimeError(1);
      }
      throw;
    }
  });
}

}  // namespace snapfit::cli
