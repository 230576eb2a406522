#include "report/run_report.h"

#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "report/accuracy_json.h"
#include "report/haptic_report.h"
#include "report/run_page.h"
#include "report/slice_figure.h"
#include "report/web_assets.h"
#include "snapfit/export.h"
#include "snapfit/inspect.h"
#include "snapfit/mesh.h"
#include "snapfit/tuning.h"

namespace snapfit {
namespace {

// A figure of the part's affinity through y = 0 of its own frame, with its outline; the
// PNG is written and kept for the page.
nlohmann::json write_affinity_figure(const std::filesystem::path& out, const Scene& scene, int part, const Mesh& mesh,
                                     const PartFieldsResult& result, std::vector<PageFigure>& figures,
                                     std::vector<std::string>& written) {
  const DescriptorFields& f = result.fields;
  const std::vector<float> rho = affinity_imaginary(f);
  const double y = std::clamp(0.0, f.grid.origin.y(), f.grid.point(0, f.grid.dims.y() - 1, 0).y());
  const int slice = slice_index_for(f.grid, 'y', y);
  const double plane = f.grid.point(0, slice, 0).y();
  const bool indicator = f.skeletal_density.empty();
  const std::string name = part == 1 ? scene.part1.name : scene.part2.name;
  SliceFigureOptions options;
  char at[48];
  std::snprintf(at, sizeof at, "%.4g", plane);
  options.title =
      "Affinity Im(rho) of part " + std::to_string(part) + " '" + name + "' at y = " + at + " " + scene.units;
  options.units = scene.units;
  options.value_label = indicator ? "Im(rho): indicator" : "Im(rho)";
  options.outline = mesh_slice_outline(mesh, 'y', plane);
  const SliceFigure fig = render_slice_figure(f.grid, rho.data(), 'y', slice,
                                              indicator ? ColorMap::sequential : ColorMap::diverging, options);
  const std::string png = "part" + std::to_string(part) + "_affinity_y0.png";
  const std::vector<std::pair<std::string, std::string>> text = {{"Title", "snapfit " + options.title}};
  write_png((out / png).string(), fig.image, text);
  written.push_back(png);
  figures.push_back({options.title + " (" + png + "; the part's outline in black)", png_bytes(fig.image, text)});
  double max_bound = 0;
  for (float b : f.density_bound) max_bound = std::max(max_bound, static_cast<double>(b));
  return {{"part", part},
          {"grid_points", f.grid.count()},
          {"dims", {f.grid.dims.x(), f.grid.dims.y(), f.grid.dims.z()}},
          {"from_cache", result.from_cache},
          {"seconds", f.seconds},
          {"max_density_bound", max_bound},
          {"affinity_png", png}};
}

// A part's mesh report, with what the CAD import did for a STEP or IGES part.
nlohmann::json part_json(const JobPart& part) {
  nlohmann::json j = nlohmann::json::parse(mesh_report_json(part.report));
  if (part.cad) j["cad"] = nlohmann::json::parse(cad_facts_json(*part.cad));
  return j;
}

}  // namespace

std::vector<std::string> write_run_report(const std::filesystem::path& out, const JobResult& run) {
  const Scene& scene = run.scene;
  std::filesystem::create_directories(out);
  std::vector<std::string> written{"summary.json"};
  for (int part = 1; part <= 2; ++part) {
    const std::string stl = "part" + std::to_string(part) + ".stl";
    write_stl(*run.part(part).mesh, (out / stl).string());
    written.push_back(stl);
  }
  std::vector<PageFigure> figures;
  nlohmann::json fields = nlohmann::json::array();
  for (int part = 1; part <= 2; ++part)
    if (run.part(part).fields)
      fields.push_back(
          write_affinity_figure(out, scene, part, *run.part(part).mesh, *run.part(part).fields, figures, written));

  nlohmann::json tuning = nullptr;
  if (!run.vps) {
    tuning = nlohmann::json::parse(tuning_to_json(run.tuning));
    tuning["key"] = run.tuning_key;
  }
  nlohmann::json strategy = nullptr;
  if (!run.vps && !run.strategy.empty()) {
    strategy = {{"name", run.strategy}, {"chosen_by", run.strategy_chosen_by}, {"why", nullptr},
                {"strategy_file", run.strategy_file.empty() ? nlohmann::json(nullptr) : nlohmann::json(run.strategy_file)},
                {"candidates", nullptr}};
    if (run.strategies) {
      strategy["why"] = run.strategies->why;
      nlohmann::json candidates = nlohmann::json::array();
      for (const StrategyAccuracy& s : run.strategies->strategies) candidates.push_back(strategy_accuracy_json(s));
      strategy["candidates"] = candidates;
      strategy["reference"] = {{"poses", run.strategies->poses}, {"modes", run.strategies->reference_modes}};
    }
  }
  nlohmann::json vps = nullptr;
  if (run.vps) {
    const VpsFacts& v = *run.vps;
    vps = {{"voxel_size", v.voxel_size},
           {"shell_spacing", v.shell_spacing},
           {"surface_voxels", v.surface_voxels},
           {"interior_voxels", v.interior_voxels},
           {"proximity_voxels", v.proximity_voxels},
           {"shell_points", v.shell_points},
           {"stiffness_n_per_m", v.stiffness_n_per_m},
           {"braking_n_s_per_m", v.braking_n_s_per_m},
           {"build_seconds", v.build_seconds}};
    if (scene.method == Method::vps_hybrid) {
      // Frames with each constraint engaged (weight > 0) and the largest weight reached.
      std::size_t concentric = 0, planar = 0;
      double max_x = 0;
      if (run.loop)
        for (const FrameRecord& f : run.loop->log) {
          if (f.constraint == 1) ++concentric;
          if (f.constraint == 2) ++planar;
          max_x = std::max(max_x, f.constraint_weight);
        }
      vps["hybrid"] = {{"engaged", v.hybrid},
                       {"plain_vps_because", v.plain_reason.empty() ? nlohmann::json(nullptr) : nlohmann::json(v.plain_reason)},
                       {"faces1", v.faces1},
                       {"faces2", v.faces2},
                       {"labelled_voxels", v.labelled_voxels},
                       {"labelled_points", v.labelled_points},
                       {"alignment_k_n_per_m", v.alignment_k_n_per_m},
                       {"frames_concentric", concentric},
                       {"frames_planar", planar},
                       {"max_constraint_x", max_x}};
    }
  }
  nlohmann::json loop = nullptr;
  if (run.session && run.loop) {
    loop = write_haptic_report(out, *run.session, *run.loop, run.tuning);
    written.push_back("loop.csv");
  }
  nlohmann::json report_html = nullptr;
  if (web_pages_available()) {
    write_run_page((out / "report.html").string(), run, figures);
    written.push_back("report.html");
    report_html = "report.html";
  }

  const nlohmann::json summary = {
      {"scene", scene.name},
      {"scene_file", scene.source_path},
      {"units", scene.units},
      {"method", method_name(scene.method)},
      {"vps", vps},
      {"device", run.device},
      {"driver", run.driver},
      {"loop_device", run.loop_device},
      {"device_check_passed", run.device_check_passed},
      {"part1", part_json(run.part1)},
      {"part2", part_json(run.part2)},
      {"plan", run.plan},
      {"spacing", run.spacing},
      {"fft_dims", run.vps ? nlohmann::json(nullptr) : nlohmann::json(run.fft_dims)},
      {"fields", fields},
      {"query_strategy", strategy},
      {"tuning", tuning},
      {"haptic_loop", loop},
      {"report_html", report_html},
      {"seconds", run.seconds},
      {"seconds_to_first_frame", run.seconds_to_first_frame},
  };
  write_text_file((out / "summary.json").string(), summary.dump(2) + "\n");
  return written;
}

RunReportFiles write_job_report(const std::filesystem::path& out, JobResult& run, double seconds) {
  run.seconds = seconds;
  RunReportFiles files;
  files.written = write_run_report(out, run);
  if (!web_pages_available())
    files.warnings.push_back(
        "no report.html: this snapfit was built with -DSNAPFIT_WEB_REPORT=OFF (no node/npm at build time)");
  if (const std::string font = figure_font_problem(); !font.empty() && !run.vps)
    files.warnings.push_back(font + ": the field figures' labels are not readable");
  return files;
}

}  // namespace snapfit
