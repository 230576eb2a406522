#include "report/run_report.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "io/atomic_write.h"
#include "io/mesh_export.h"
#include "io/png_export.h"
#include "mesh/mesh_report.h"
#include "report/haptic_report.h"
#include "scheduler/tuning_file.h"

namespace snapfit {
namespace {

// A slice of the part's affinity through y = 0 of its own frame, and its summary.
nlohmann::json write_affinity_slice(const std::filesystem::path& out, int part, const PartFieldsResult& result,
                                    std::vector<std::string>& written) {
  const DescriptorFields& f = result.fields;
  const std::vector<float> rho = affinity_imaginary(f);
  const int slice =
      slice_index_for(f.grid, 'y', std::clamp(0.0, f.grid.origin.y(), f.grid.point(0, f.grid.dims.y() - 1, 0).y()));
  const ColorMap map = f.skeletal_density.empty() ? ColorMap::sequential : ColorMap::diverging;
  const std::string png = "part" + std::to_string(part) + "_affinity_y0.png";
  write_png((out / png).string(), render_slice(f.grid, rho.data(), 'y', slice, map, std::nullopt, 4),
            {{"Title", "snapfit affinity Im(rho) of part " + std::to_string(part) + " at y=0"}});
  written.push_back(png);
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
nlohmann::json part_json(const PreparedPart& part) {
  nlohmann::json j = nlohmann::json::parse(mesh_report_json(part.report));
  if (part.cad) j["cad"] = nlohmann::json::parse(cad_facts_json(*part.cad));
  return j;
}

}  // namespace

std::vector<std::string> write_run_report(const std::filesystem::path& out, const RunRecord& run) {
  const AssemblyPair& pair = *run.pair;
  const Scene& scene = pair.scene;
  std::filesystem::create_directories(out);
  std::vector<std::string> written{"summary.json"};
  for (int part = 1; part <= 2; ++part) {
    const std::string stl = "part" + std::to_string(part) + ".stl";
    write_stl(pair.part(part).mesh, (out / stl).string());
    written.push_back(stl);
  }
  nlohmann::json fields = nlohmann::json::array();
  for (int part = 1; part <= 2; ++part) fields.push_back(write_affinity_slice(out, part, pair.fields(part), written));

  nlohmann::json tuning = nlohmann::json::parse(tuning_to_json(run.tuning));
  tuning["key"] = run.tuning_key;
  nlohmann::json loop = nullptr;
  if (run.session) {
    loop = write_haptic_report(out, scene, *run.session, run.tuning);
    for (const char* f : {"loop.csv", "frame_times.png", "energy.png", "force_torque.png", "pose_error.png"})
      written.push_back(f);
  } else {
    write_chart_png((out / "tuning.png").string(), tuning_chart(run.tuning, run.loop_device.name));
  }
  written.push_back("tuning.png");

  const nlohmann::json summary = {
      {"scene", scene.name},
      {"scene_file", scene.source_path},
      {"units", scene.units},
      {"device", run.device.name},
      {"driver", run.device.driver_version},
      {"loop_device", run.loop_device.name},
      {"device_check_passed", run.check.passed},
      {"part1", part_json(pair.parts.part1)},
      {"part2", part_json(pair.parts.part2)},
      {"plan", pair.plan.lines},
      {"spacing", pair.grids.spacing},
      {"fft_dims", pair.spectra.dims},
      {"fields", fields},
      {"tuning", tuning},
      {"haptic_loop", loop},
      {"seconds", run.seconds},
  };
  write_text_file((out / "summary.json").string(), summary.dump(2) + "\n");
  return written;
}

}  // namespace snapfit
