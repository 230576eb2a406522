// `snapfit run SCENE`: the main job. Today it loads the scene, builds and validates
// both parts in parallel, opens the OpenCL device, builds (or loads from the program
// cache) and self-checks the kernels, prints the compute plan, computes (or loads from
// the field cache) both parts' descriptor fields, and writes a report folder with the
// part meshes, a PNG slice of each part's affinity and a JSON summary, then computes
// (or loads) the spectra and evaluates energy, force and torque along the scene's
// scripted trajectory (CSV + charts). The haptic loop (issue 5) adds its step here.
#include <algorithm>
#include <chrono>
#include <optional>
#include <sstream>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "cli/scene_summary.h"
#include "engine/device_check.h"
#include "engine/error.h"
#include "engine/assembly_pair.h"
#include "engine/part_fields.h"
#include "io/plot.h"
#include "io/spectra_cache.h"
#include "scheduler/trajectory.h"
#include "io/png_export.h"
#include "scheduler/progress.h"
#include "io/mesh_export.h"
#include "io/atomic_write.h"
#include "io/mesh_report.h"

namespace snapfit::cli {
namespace {

struct RunOptions {
  std::string scene;
  std::string device;
  std::string out;
  std::size_t modes = 32768;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void run_main_job(const RunOptions& opt) {
  namespace fs = std::filesystem;
  const auto start = std::chrono::steady_clock::now();
  std::cout << "[1/6] reading scene " << opt.scene << "\n";
  const Scene scene = load_scene(opt.scene);

  std::cout << "[2/6] building and validating both parts (in parallel)\n";
  const PreparedParts parts = prepare_parts(scene);
  const ComputePlan plan = plan_computation(scene);
  print_scene_summary(std::cout, scene, parts, plan);

  std::cout << "[3/6] opening the OpenCL device and checking it\n";
  const Device device = select_device(device_spec_from(opt.device));
  std::cout << "    device " << describe_device(device.info) << "\n";
  const ComputeContext ctx = make_compute_context(device);
  const DeviceCheckResult check = run_device_check(ctx, false);
  std::cout << "    self-check " << (check.passed ? "passed" : "FAILED") << " (relative error " << check.relative_error
            << ", program " << (check.origin == ProgramOrigin::cache_hit ? "from cache" : "compiled") << " in "
            << check.build_ms << " ms)\n";
  if (!check.passed) throw Error("device " + device.info.name + " failed its self-check; choose another with --device");

  const ScenePartGrids grids = scene_part_grids(scene.grid, parts.part1.mesh, parts.part2.mesh);
  std::cout << "[4/6] descriptor fields of both parts at spacing " << grids.spacing << " " << scene.units
            << " (from the field cache when present)\n";
  DescriptorOptions options;
  options.progress = pass_progress_bars();
  const auto note = [](const std::string& m) { std::cerr << "snapfit: " << m << "\n"; };
  std::vector<PartFieldsResult> fields;
  for (int part = 1; part <= 2; ++part) {
    const Mesh& mesh = part == 1 ? parts.part1.mesh : parts.part2.mesh;
    const GridSpec& grid = part == 1 ? grids.part1 : grids.part2;
    std::cout << "  part " << part << ": grid " << grid.dims.x() << " x " << grid.dims.y() << " x " << grid.dims.z()
              << " = " << grid.count() << " points, " << mesh.triangles.size() << " triangles" << std::endl;
    fields.push_back(part_fields(ctx, mesh, grid, scene.descriptor, options, true, note));
    print_fields_summary(std::cout, fields.back());
  }

  // Spectra (cached) and the scripted trajectory through the per-pose engine.
  const bool torque = plan.torque_fields;
  std::cout << "[5/6] spectra and energy, force" << (torque ? ", torque" : "") << " along the scripted trajectory\n";
  const FftLibrary fft;
  const SpectrumOptions spectrum_options;
  const std::string spectra_key = spectra_cache_key(fields[0].fields, fields[1].fields, torque, spectrum_options);
  std::optional<PairSpectra> spectra = load_cached_spectra(spectra_key, note);
  if (!spectra) {
    spectra = compute_pair_spectra(fft, ctx, fields[0].fields, fields[1].fields, torque, spectrum_options);
    save_cached_spectra(spectra_key, *spectra, note);
  }
  std::cout << "    FFT grid " << spectra->dims[0] << " x " << spectra->dims[1] << " x " << spectra->dims[2] << "\n";
  PoseQueryEngine engine(ctx, *spectra, query_variant_for(scene, Interpolation::tricubic));
  engine.set_modes(opt.modes);
  std::vector<Pose> trajectory;
  std::vector<QueryResult> along;
  const double sample_hz = 100.0;
  if (!scene.trajectory.keyframes.empty()) {
    trajectory = sample_trajectory(scene.trajectory, sample_hz);
    along = engine.query_batch(trajectory);
    std::cout << "    " << trajectory.size() << " poses at " << sample_hz << " Hz, m' = " << engine.modes() << " modes, "
              << along.front().seconds * 1e3 << " ms per pose in one batch\n";
  }

  const fs::path out = opt.out.empty() ? fs::path("results") / fs::path(opt.scene).stem() : fs::path(opt.out);
  std::cout << "[6/6] writing the report to " << out.string() << "\n";
  fs::create_directories(out);
  write_stl(parts.part1.mesh, (out / "part1.stl").string());
  write_stl(parts.part2.mesh, (out / "part2.stl").string());
  // A slice of each part's affinity through y = 0 of its own frame (seed 000 Fig. 2 style).
  nlohmann::json field_summary = nlohmann::json::array();
  for (int part = 1; part <= 2; ++part) {
    const DescriptorFields& f = fields[part - 1].fields;
    const std::vector<float> rho = affinity_imaginary(f);
    const int slice = slice_index_for(f.grid, 'y', std::clamp(0.0, f.grid.origin.y(), f.grid.point(0, f.grid.dims.y() - 1, 0).y()));
    const ColorMap map = f.skeletal_density.empty() ? ColorMap::sequential : ColorMap::diverging;
    const std::string png = "part" + std::to_string(part) + "_affinity_y0.png";
    write_png((out / png).string(), render_slice(f.grid, rho.data(), 'y', slice, map, std::nullopt, 4),
              {{"Title", "snapfit affinity Im(rho) of part " + std::to_string(part) + " at y=0"}});
    double max_bound = 0;
    for (float b : f.density_bound) max_bound = std::max(max_bound, static_cast<double>(b));
    field_summary.push_back({{"part", part},
                             {"grid_points", f.grid.count()},
                             {"dims", {f.grid.dims.x(), f.grid.dims.y(), f.grid.dims.z()}},
                             {"from_cache", fields[part - 1].from_cache},
                             {"seconds", f.seconds},
                             {"max_density_bound", max_bound},
                             {"affinity_png", png}});
  }
  // Energy, force and torque along the trajectory: CSV and charts.
  nlohmann::json trajectory_summary = nullptr;
  if (!trajectory.empty()) {
    std::string csv = "time_s,x,y,z,qw,qx,qy,qz,energy,fx,fy,fz,tx,ty,tz,flags\n";
    Series energy{"energy", {}, {}, Series::Style::line}, force{"|force|", {}, {}, Series::Style::line},
        torque_norm{"|torque|", {}, {}, Series::Style::line};
    std::size_t best = 0;
    for (std::size_t i = 0; i < trajectory.size(); ++i) {
      const double t = scene.trajectory.keyframes.front().time_s + i / sample_hz;
      const Pose& p = trajectory[i];
      const QueryResult& r = along[i];
      std::ostringstream row;
      row.precision(9);
      row << t << "," << p.translation.x() << "," << p.translation.y() << "," << p.translation.z() << ","
          << p.rotation.w() << "," << p.rotation.x() << "," << p.rotation.y() << "," << p.rotation.z() << "," << r.energy
          << "," << r.force.x() << "," << r.force.y() << "," << r.force.z() << "," << r.torque.x() << ","
          << r.torque.y() << "," << r.torque.z() << "," << r.flags << "\n";
      csv += row.str();
      if (r.flags) continue;
      energy.x.push_back(t);
      energy.y.push_back(r.energy);
      force.x.push_back(t);
      force.y.push_back(r.force.norm());
      torque_norm.x.push_back(t);
      torque_norm.y.push_back(r.torque.norm());
      if (r.energy < along[best].energy || along[best].flags) best = i;
    }
    write_file_atomically((out / "trajectory.csv").string(), [&](std::FILE* f) {
      return std::fwrite(csv.data(), 1, csv.size(), f) == csv.size() ? std::string() : std::string("short write");
    });
    Chart e_chart{"Geometric energy along the scripted trajectory (" + scene.name + ")", "time (s)", "energy", false,
                  false, {energy}, {}, {}};
    write_chart_png((out / "energy.png").string(), e_chart);
    Chart ft_chart{"Force and torque magnitude along the trajectory", "time (s)", "magnitude", false, false,
                   {force}, {}, {}};
    if (torque) ft_chart.series.push_back(torque_norm);
    write_chart_png((out / "force_torque.png").string(), ft_chart);
    const QueryResult& last = along.back();
    trajectory_summary = {{"poses", trajectory.size()},
                          {"sample_hz", sample_hz},
                          {"modes", engine.modes()},
                          {"ms_per_pose_batched", along.front().seconds * 1e3},
                          {"lowest_energy", along[best].energy},
                          {"lowest_energy_time_s", scene.trajectory.keyframes.front().time_s + best / sample_hz},
                          {"final_energy", last.energy},
                          {"final_force", {last.force.x(), last.force.y(), last.force.z()}},
                          {"final_torque", {last.torque.x(), last.torque.y(), last.torque.z()}}};
    std::cout << "    lowest energy " << along[best].energy << " at t = " << best / sample_hz << " s; at the end E = "
              << last.energy << ", |F| = " << last.force.norm() << ", |T| = " << last.torque.norm() << "\n";
  }

  nlohmann::json summary = {
      {"scene", scene.name},
      {"scene_file", scene.source_path},
      {"units", scene.units},
      {"device", device.info.name},
      {"driver", device.info.driver_version},
      {"device_check_passed", check.passed},
      {"part1", nlohmann::json::parse(mesh_report_json(parts.part1.report))},
      {"part2", nlohmann::json::parse(mesh_report_json(parts.part2.report))},
      {"plan", plan.lines},
      {"spacing", grids.spacing},
      {"fields", field_summary},
      {"trajectory", trajectory_summary},
      {"seconds", seconds_since(start)},
  };
  std::ofstream(out / "summary.json") << summary.dump(2) << "\n";
  std::cout << "done in " << seconds_since(start) << " s: " << (out / "summary.json").string()
            << ", part1.stl, part2.stl, part1_affinity_y0.png, part2_affinity_y0.png"
            << (trajectory.empty() ? "" : ", trajectory.csv, energy.png, force_torque.png") << "\n";
}

}  // namespace

void add_run_command(CLI::App& app) {
  auto opt = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "The main job: prepare a scene's parts and device, write a report folder");
  cmd->add_option("scene", opt->scene, "Scene file (JSON, see scenes/README.md)")->required();
  cmd->add_option("--device", opt->device, "OpenCL device: index, platform:device, cpu|gpu|accelerator, or a name substring (default: $SNAPFIT_DEVICE, else PoCL's CPU device)");
  cmd->add_option("--out", opt->out, "Report folder (default: results/<scene name>)");
  cmd->add_option("--modes", opt->modes, "m': Fourier modes per query along the trajectory");
  cmd->callback([opt] { run_main_job(*opt); });
}

}  // namespace snapfit::cli
