// `snapfit fields SCENE`: compute (or load from the cache) the descriptor fields of a
// scene's parts and export them: VTK image data for ParaView, and a PNG slice like
// seed 000 Fig. 2 and Fig. 5 (top row).
#include <cstdio>
#include <iostream>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "report/slice_figure.h"
#include "snapfit/error.h"
#include "snapfit/export.h"
#include "snapfit/fields.h"

namespace snapfit::cli {
namespace {

struct FieldsOptions {
  std::string scene;
  std::string part = "2";
  std::string device;
  std::string slice = "z=0";
  std::string field = "rho";
  std::string png;
  std::string vti;
  int pixels = 0;  // 0: automatic (report/slice_figure.h)
  bool no_cache = false;
};

const std::vector<float>& pick_field(const DescriptorFields& f, const std::vector<float>& rho,
                                     const std::string& name) {
  if (name == "rho") return rho;
  if (name == "w") return f.winding;
  if (name == "s" || name == "bound" || name == "xi") {
    if (f.skeletal_density.empty())
      throw Error("--field " + name +
                  ": the scene's descriptor is the indicator (collision response only), which computes the winding "
                  "number alone");
    return name == "s" ? f.skeletal_density : name == "xi" ? f.signed_distance : f.density_bound;
  }
  throw Error("--field: expected rho, s, w, xi or bound (got '" + name + "')");
}

std::string field_title(const std::string& name) {
  if (name == "rho") return "Affinity Im(rho)";
  if (name == "s") return "Skeletal density s";
  if (name == "w") return "Winding number w";
  if (name == "xi") return "Signed distance xi";
  return "Skeletal density error bound";
}

std::string number(double v) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

// The slice as a figure with the part's outline, written to --png.
void write_figure(const FieldsOptions& opt, const Scene& scene, const ScenePartFields& part) {
  const DescriptorFields& f = part.result.fields;
  const std::vector<float> rho = affinity_imaginary(f);
  const std::vector<float>& values = pick_field(f, rho, opt.field);
  const ColorMap map = opt.field == "bound" || (opt.field == "rho" && f.skeletal_density.empty()) ? ColorMap::sequential
                                                                                                  : ColorMap::diverging;
  const char axis = opt.slice[0];
  const char* axis_name = axis == 'x' ? "x" : axis == 'y' ? "y" : "z";
  const double plane = part.slice_plane;
  SliceFigureOptions figure;
  figure.title = field_title(opt.field) + " of part " + opt.part + " '" +
                 (opt.part == "1" ? scene.part1.name : scene.part2.name) + "' at " + axis_name + " = " + number(plane) +
                 " " + scene.units;
  figure.units = scene.units;
  figure.value_label = opt.field;
  figure.outline = part.outline;
  figure.pixels_per_point = opt.pixels;
  const SliceFigure fig =
      write_slice_figure(opt.png, part.grid, values.data(), axis, part.slice_index, map, figure, true);
  std::cout << "wrote " << opt.png << " (" << fig.image.width << " x " << fig.image.height << " pixels, " << opt.field
            << " at " << axis_name << " = " << plane << ", colour range [" << fig.image.value_min << ", "
            << fig.image.value_max << "], the part's outline in black)\n";
}

void run_fields(const FieldsOptions& opt) {
  const Scene scene = load_scene(opt.scene);
  if (opt.part != "1" && opt.part != "2") throw Error("--part: expected 1 or 2 (got '" + opt.part + "')");
  PartFieldsRequest request;
  request.part = opt.part == "1" ? 1 : 2;
  request.slice = parse_slice(opt.slice);
  request.device = opt.device;
  request.progress = true;
  request.use_cache = !opt.no_cache;
  const ScenePartFields part = scene_part_fields(scene, request);
  const GridSpec& grid = part.grid;
  std::cout << "part " << opt.part << ": " << part.triangles << " triangles, grid " << grid.dims.x() << " x "
            << grid.dims.y() << " x " << grid.dims.z() << " = " << grid.count() << " points at spacing " << grid.spacing
            << " " << scene.units << ", on " << part.device << "\n";
  std::cout << fields_summary_text(part.result);

  const DescriptorFields& f = part.result.fields;
  if (!opt.vti.empty()) {
    const std::vector<float> rho = affinity_imaginary(f);
    std::vector<GridField> out = {{"w", f.winding.data()}, {"rho_imag", rho.data()}};
    if (!f.skeletal_density.empty()) {
      out.push_back({"xi", f.signed_distance.data()});
      out.push_back({"s", f.skeletal_density.data()});
      out.push_back({"s_error_bound", f.density_bound.data()});
    }
    write_vti(opt.vti, grid, out);
    std::cout << "wrote " << opt.vti << "\n";
  }
  if (!opt.png.empty()) write_figure(opt, scene, part);
}

}  // namespace

void add_fields_command(CLI::App& app) {
  auto opt = std::make_shared<FieldsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "fields", "Compute a part's descriptor fields (cached) and export a PNG slice and/or a .vti volume");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option("--part", opt->part, "Which part: 1 (fixed) or 2 (moving)");
  cmd->add_option("--slice", opt->slice, "Slice for the PNG: x=V, y=V or z=V in the part's frame (scene units)");
  cmd->add_option("--field", opt->field, "Field for the PNG: rho (affinity, Im), s, w, xi, bound");
  cmd->add_option("--png", opt->png, "Write the slice as a PNG image");
  cmd->add_option("--vti", opt->vti, "Write every field as VTK image data (ParaView)");
  cmd->add_option("--pixels", opt->pixels, "Pixels per grid point in the PNG (default: the slice 480 pixels or more)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--device", opt->device, "OpenCL device (see `snapfit devices`)");
  cmd->add_flag("--no-cache", opt->no_cache, "Recompute even if the field cache has the fields");
  cmd->callback([opt] { run_fields(*opt); });
}

}  // namespace snapfit::cli
