// `snapfit search SCENE`: where part 2 fits part 1 over all rotations. One full
// translational energy map per rotation of a uniform SO(3) grid (core/so3_grid.h,
// engine/maps/rotation_search.h), the best poses of all maps merged, each refined by a
// local 6-DOF descent with the query engine (engine/query/pose_descent.h) and, with the
// scene's rigid contact, of the potential the haptic loop renders
// (scheduler/rendered_wrench.h). Under mpirun the
// ranks share the rotations cyclically, each on its own OpenCL device
// (cli/search_ranks.h); rank 0 merges, refines and reports.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "cli/search_ranks.h"
#include "core/progress.h"
#include "core/so3_grid.h"
#include "engine/maps/map_fft_choice.h"
#include "engine/maps/rotation_search.h"
#include "engine/query/pose_descent.h"
#include "engine/query/query_engine.h"
#include "io/atomic_write.h"
#include "pipeline/assembly_pair.h"
#include "report/chart_spec.h"
#include "scheduler/haptic_setup.h"
#include "scheduler/mode_tuning.h"
#include "scheduler/rendered_wrench.h"
#include "scheduler/rigid_contact.h"
#include "snapfit/error.h"

namespace snapfit::cli {
namespace {

constexpr double kDeg = M_PI / 180.0;

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
  std::string map_fft = "auto";  // auto: measured per (device, size), engine/maps/map_fft_choice.h
  std::size_t map_batch = 0;     // rotations per batch; 0: the measured pick with auto, else 1
};

std::string device_for_rank(const std::string& list, int local_rank) {
  std::vector<std::string> specs;
  std::stringstream in(list);
  std::string item;
  while (std::getline(in, item, ';')) specs.push_back(item);
  if (specs.empty()) return device_spec_from("");
  return device_spec_from(specs[std::size_t(local_rank) % specs.size()]);
}

nlohmann::json pose_json(const Pose& pose) {
  const Eigen::AngleAxisd aa(pose.rotation);
  const bool turned = std::abs(aa.angle()) > 1e-12;
  const Eigen::Vector3d axis = turned ? aa.axis() : Eigen::Vector3d::UnitZ();
  return {{"position", {pose.translation.x(), pose.translation.y(), pose.translation.z()}},
          {"rotation_axis", {axis.x(), axis.y(), axis.z()}},
          {"rotation_deg", turned ? aa.angle() / kDeg : 0.0}};
}

// Each candidate as (rotation, cell, energy, t) doubles, and back.
std::vector<double> pack(const std::vector<PoseCandidate>& cs) {
  std::vector<double> v;
  for (const PoseCandidate& c : cs)
    v.insert(v.end(), {double(c.rotation), double(c.cell), c.energy, c.pose.translation.x(), c.pose.translation.y(),
                       c.pose.translation.z()});
  return v;
}

std::vector<PoseCandidate> unpack(const std::vector<double>& v, const So3Grid& grid) {
  std::vector<PoseCandidate> cs;
  for (std::size_t i = 0; i + 6 <= v.size(); i += 6) {
    PoseCandidate c;
    c.rotation = std::size_t(v[i]);
    c.cell = std::size_t(v[i + 1]);
    c.energy = v[i + 2];
    c.pose.rotation = grid.rotations[c.rotation];
    c.pose.translation = Eigen::Vector3d(v[i + 3], v[i + 4], v[i + 5]);
    cs.push_back(c);
  }
  return cs;
}

void write_best_per_rotation(const std::string& dir, const So3Grid& grid, const std::vector<double>& best,
                             const std::vector<PoseCandidate>& top, const std::string& title) {
  std::filesystem::create_directories(dir);
  std::ostringstream csv;
  csv << "rotation,axis_x,axis_y,axis_z,angle_deg,best_energy\n";
  Series series;
  series.label = "lowest E of the rotation's map";
  series.style = Series::Style::points;
  for (std::size_t r = 0; r < best.size(); ++r) {
    const nlohmann::json p = pose_json(Pose{grid.rotations[r], Eigen::Vector3d::Zero()});
    char line[256];
    std::snprintf(line, sizeof line, "%zu,%.9g,%.9g,%.9g,%.9g,%.9g\n", r, double(p["rotation_axis"][0]),
                  double(p["rotation_axis"][1]), double(p["rotation_axis"][2]), double(p["rotation_deg"]), best[r]);
    csv << line;
    series.x.push_back(double(r));
    series.y.push_back(best[r]);
  }
  write_text_file(dir + "/best_per_rotation.csv", csv.str());
  Chart chart;
  chart.title = "Best energy per rotation";
  chart.x_label = "rotation index (base cell, then turn about it)";
  chart.y_label = "lowest E over translations";
  chart.series.push_back(series);
  for (std::size_t k = 0; k < top.size(); ++k)
    chart.markers.push_back({double(top[k].rotation), top[k].energy, "#" + std::to_string(k + 1)});
  write_chart_page(dir + "/search.html", "snapfit search: " + title,
                   {std::to_string(best.size()) + " rotations; best_per_rotation.csv holds the values"}, {chart});
}

void run_search(const SearchOptions& opt, const SearchRanks& ranks) {
  if (opt.step_deg && opt.rotations) throw Error("--step-deg and --rotations: give one of them");
  if (!opt.out.empty() && ranks.rank() == 0) check_output_folder(opt.out);
  const So3Grid grid =
      opt.rotations ? so3_grid_for_count(*opt.rotations) : so3_grid_for_step(opt.step_deg.value_or(30.0) * kDeg);
  const Interpolation interpolation = parse_interpolation(opt.interpolation);
  // Rank 0 builds the pair (fields and spectra, cached); the others get its spectra.
  AssemblyPair pair;
  std::string error;
  if (ranks.root()) {
    try {
      Scene scene = load_scene(opt.scene);
      scene.motion = Motion::six_dof;  // part 2 in its own frame: the search turns it
      const ComputeContext ctx = make_compute_context(select_device(device_for_rank(opt.devices, 0)));
      const FftLibrary fft;
      PairOptions options;
      options.descriptors.progress = pass_progress_bars();
      pair = build_assembly_pair(scene, ctx, fft, options);
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  ranks.checkpoint(error);
  ranks.broadcast(pair.spectra);

  // Every rank: its device, the mapper, its share of the rotations (r = rank mod ranks).
  std::unique_ptr<ComputeContext> ctx;
  std::unique_ptr<FftLibrary> fft;
  std::unique_ptr<TranslationMapper> mapper;
  std::string fft_used;
  // Rank 0 measures the inverse FFTs first (alone on the machine), so the other ranks on
  // the same kind of device find its pick in the cache.
  auto make_mapper = [&] {
    try {
      ctx = std::make_unique<ComputeContext>(
          make_compute_context(select_device(device_for_rank(opt.devices, ranks.local_rank()))));
      fft = std::make_unique<FftLibrary>();
      MapFft kind = MapFft::clfft;
      std::size_t batch = opt.map_batch ? opt.map_batch : 1;
      if (opt.map_fft == "auto") {
        const MapFftChoice choice = choose_map_fft(*fft, *ctx, pair.spectra, interpolation, opt.modes);
        kind = choice.fft;
        if (!opt.map_batch) batch = choice.batch;
        fft_used = describe_map_fft_choice(choice);
      } else {
        kind = parse_map_fft(opt.map_fft);
        fft_used = map_fft_name(kind) + " (--map-fft)";
      }
      if (opt.map_batch)
        fft_used +=
            ", " + std::to_string(batch) + (batch == 1 ? " rotation" : " rotations") + " per batch (--map-batch)";
      mapper = std::make_unique<TranslationMapper>(*fft, *ctx, pair.spectra, interpolation, opt.modes, kind,
                                                   default_program_cache(), batch);
    } catch (const std::exception& e) {
      error = e.what();
    }
  };
  if (ranks.root()) make_mapper();
  ranks.checkpoint(error);
  if (!ranks.root()) make_mapper();
  ranks.checkpoint(error);
  if (ranks.root()) {
    const auto& d = pair.spectra.dims;
    std::cout << "SO(3) grid: " << grid.rotations.size() << " rotations (" << grid.base_cells << " directions x "
              << grid.psi_steps << " turns, step " << grid.step_rad / kDeg << " deg), covering radius "
              << so3_covering_radius(grid) / kDeg << " deg\n"
              << "maps: " << d[0] << " x " << d[1] << " x " << d[2] << " translations, spacing " << pair.spectra.spacing
              << " " << pair.scene.units << ", " << opt.interpolation << ", " << ranks.size()
              << (ranks.size() == 1 ? " rank" : " ranks") << "\n"
              << "map FFT: " << fft_used << "\n"
              << "map minima: "
              << (mapper->minima_on_device() ? "on the device, a short list read back per map"
                                             : "on the host, in each map read back")
              << "\n";
  }
  std::vector<std::size_t> mine;
  for (std::size_t r = std::size_t(ranks.rank()); r < grid.rotations.size(); r += std::size_t(ranks.size()))
    mine.push_back(r);
  ScanOptions scan_options;
  scan_options.minima_per_rotation = opt.per_rotation;
  scan_options.separation = 2 * pair.spectra.spacing;
  RotationScan scan;
  double seconds = 0;
  try {
    // Rank 0 shows the bar, counting each of its maps once per rank (the ranks keep pace).
    std::unique_ptr<Progress> progress;
    if (ranks.root()) {
      progress = std::make_unique<Progress>("rotations", grid.rotations.size());
      progress->show_rate("rotations");
    }
    const auto start = std::chrono::steady_clock::now();
    scan = scan_rotations(*mapper, grid.rotations, mine, scan_options, [&] {
      if (progress) progress->advance(std::size_t(ranks.size()));
    });
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (progress) progress->finish();
  } catch (const std::exception& e) {
    error = e.what();
  }
  ranks.checkpoint(error);
  std::vector<double> best_mine;
  for (std::size_t i = 0; i < scan.rotations.size(); ++i)
    best_mine.insert(best_mine.end(), {double(scan.rotations[i]), scan.best_energy[i]});
  const std::vector<double> all_best = ranks.gather(best_mine);
  const std::vector<double> all_candidates = ranks.gather(pack(scan.candidates));
  const std::vector<double> rates = ranks.gather({double(mine.size()), seconds});
  if (!ranks.root()) return;

  for (int r = 0; r < ranks.size(); ++r)
    std::cout << "rank " << r << ": " << rates[2 * r] << " rotations in " << rates[2 * r + 1] << " s ("
              << rates[2 * r] / rates[2 * r + 1] << " rotations/s)\n";
  std::vector<double> best(grid.rotations.size(), std::nan(""));
  for (std::size_t i = 0; i + 2 <= all_best.size(); i += 2) best[std::size_t(all_best[i])] = all_best[i + 1];
  const std::vector<PoseCandidate> top =
      merge_candidates(unpack(all_candidates, grid), opt.top, 2 * pair.spectra.spacing, grid.step_rad);

  // Refinement on rank 0's device with the per-frame query engine: a descent of the
  // energy, then (with the scene's rigid contact) of the potential the haptic loop
  // renders, the energy times the loop's gain plus the contact, from where the first
  // ended. The energy alone may be lowest inside part 1 (below a blind hole's floor);
  // the rendered potential rests where the parts touch.
  QueryVariant variant;
  variant.force = variant.torque = true;
  variant.interpolation = Interpolation::tricubic;
  auto engine = make_query_engine(*ctx, pair.spectra, variant);
  const double spacing = pair.spectra.spacing;
  std::shared_ptr<const RigidContactModel> contact;
  LoopConfig loop;
  if (pair.scene.haptics.contact) {
    contact = rigid_contact_for(pair.scene, pair.part(1).mesh, pair.part(2).mesh, spacing);
    const TuningResult at_refine_modes =
        pick_modes({TimingPoint{opt.refine_modes, 0, 0, 0, 1}}, pair.scene.frame_budget_ms, 0.25);
    double force_scale = 0;
    loop = loop_config_for(pair.scene, pair.part(2).mesh, spacing, *engine, at_refine_modes, force_scale, contact);
  }
  engine->set_modes(opt.refine_modes);
  DescentOptions descent;
  descent.length = pair.spectra.part2.half_extent.norm();
  descent.step = spacing;
  descent.min_step = spacing / 100;
  descent.max_queries = opt.refine_queries;
  std::ostringstream lines;
  for (std::size_t k = 0; k < top.size(); ++k) {
    nlohmann::json line = pose_json(top[k].pose);
    line["rank"] = k + 1;
    line["energy"] = top[k].energy;
    line["map_fft"] = map_fft_name(mapper->fft());
    line["map_batch"] = mapper->batch();
    try {
      const DescentResult refined = descend_pose(*engine, top[k].pose, descent);
      nlohmann::json by_energy = pose_json(refined.pose);
      by_energy["energy"] = refined.energy;
      by_energy["queries"] = refined.queries;
      nlohmann::json r = by_energy;
      r["by"] = "energy";
      if (contact) {
        const RestPoint rest =
            descend_rendered(wrench_evaluator(*engine), loop.geometry_gain, loop.contact, loop.coupling, refined.pose);
        r = pose_json(rest.pose);
        r["by"] = "rendered potential (energy x gain + rigid contact)";
        r["energy"] = engine->query(rest.pose).energy;
        r["potential_j"] = rest.potential_j;
        r["newton_steps"] = rest.steps;
        r["energy_minimum"] = by_energy;
      }
      r["modes"] = engine->modes();
      line["refined"] = r;
    } catch (const Error& e) {
      line["refined"] = {{"error", e.what()}};
    }
    lines << line.dump() << "\n";
  }
  std::cout << lines.str();
  if (!opt.out.empty()) {
    write_best_per_rotation(opt.out, grid, best, top, pair.scene.name);
    write_text_file(opt.out + "/top.jsonl", lines.str());
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
  cmd->add_option("--map-fft", opt->map_fft,
                  "Inverse FFT of the maps: auto (the fastest, measured once per device and size), clfft, fftw or "
                  "vkfft (those this build has)");
  cmd->add_option("--map-batch", opt->map_batch,
                  "Rotations mapped per batch on a device FFT (default: measured with --map-fft auto, else 1)")
      ->check(positive_number());
  cmd->callback([opt] {
    const SearchRanks ranks;
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
