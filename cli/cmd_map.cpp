// `snapfit map SCENE --rotation ...`: the energy for every translation of part 2 at
// one rotation (a C-space slice, Behandish & Ilies 2016 Fig. 5 bottom row), as a PNG slice and/or a
// .vti volume.
#include <cstdio>
#include <iostream>
#include <sstream>

#include "cli/commands.h"
#include "cli/parse_options.h"
#include "report/slice_figure.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/export.h"
#include "snapfit/maps.h"

namespace snapfit::cli {
namespace {

struct MapOptions {
  std::string scene;
  std::string rotation;  // ax,ay,az,deg
  std::string slice = "x=0";
  std::string png, vti;
  std::size_t modes = 0;
  std::string device;
  int pixels = 0;  // 0: automatic (report/slice_figure.h)
};

Eigen::Matrix3d parse_rotation(const std::string& text) {
  if (text.empty()) return Eigen::Matrix3d::Identity();
  std::vector<double> v;
  std::stringstream in(text);
  std::string item;
  try {
    while (std::getline(in, item, ',')) v.push_back(std::stod(item));
  } catch (const std::exception&) {
    throw Error("--rotation: '" + item + "' is not a number (format: ax,ay,az,angle_deg)");
  }
  if (v.size() != 4) throw Error("--rotation: expected ax,ay,az,angle_deg");
  const Eigen::Vector3d axis(v[0], v[1], v[2]);
  if (!(axis.norm() > 0) || !std::isfinite(v[3]))
    throw Error("--rotation: the axis must be non-zero and the angle finite");
  return Eigen::AngleAxisd(v[3] * M_PI / 180.0, axis.normalized()).toRotationMatrix();
}

void run_map(const MapOptions& opt) {
  const Scene scene = load_scene(opt.scene);
  const Eigen::Matrix3d R = parse_rotation(opt.rotation);
  const auto [axis, coordinate] = parse_slice(opt.slice);
  AssemblyOptions options;
  options.device = opt.device;
  options.progress = true;
  const Assembly assembly(scene, options);
  TranslationMapRequest request;
  request.rotation = R;
  request.modes = opt.modes;
  const TranslationMap map = translational_energy_map(assembly, request);
  std::cout << "map of " << map.grid.count() << " translations (" << map.grid.dims.x() << " x " << map.grid.dims.y()
            << " x " << map.grid.dims.z() << ", spacing " << map.grid.spacing << " " << scene.units << ") in "
            << map.seconds << " s\n";
  if (!opt.vti.empty()) {
    write_vti(opt.vti, map.grid, {{"energy", map.energy.data()}});
    std::cout << "wrote " << opt.vti << "\n";
  }
  if (!opt.png.empty()) {
    const int index = slice_index_for(map.grid, axis, coordinate);
    // Energy: negative (fit, red would read as "hot"): show -E so fits are red, collisions blue.
    std::vector<float> score(map.energy.size());
    for (std::size_t i = 0; i < score.size(); ++i) score[i] = -map.energy[i];
    SliceFigureOptions figure;
    char plane[48];
    std::snprintf(plane, sizeof plane, "%.4g", map.grid.origin[axis - 'x'] + map.grid.spacing * index);
    figure.title = "-E over translations of part 2 at " + std::string(1, axis) + " = " + plane + " " + scene.units +
                   (opt.rotation.empty() ? std::string() : ", rotation " + opt.rotation);
    figure.units = scene.units;
    figure.value_label = "-E (red: fit)";
    figure.pixels_per_point = opt.pixels;
    const SliceFigure fig =
        write_slice_figure(opt.png, map.grid, score.data(), axis, index, ColorMap::diverging, figure);
    std::cout << "wrote " << opt.png << " (-E at " << opt.slice
              << ": red = fit, blue = collision or separation; range [" << fig.image.value_min << ", "
              << fig.image.value_max << "], magenta = aliased)\n";
  }
}

}  // namespace

void add_map_command(CLI::App& app) {
  auto opt = std::make_shared<MapOptions>();
  CLI::App* cmd = app.add_subcommand("map", "Energy for every translation of part 2 at one rotation (full map by FFT)");
  cmd->add_option("scene", opt->scene, "Scene file (JSON)")->required();
  cmd->add_option("--rotation", opt->rotation, "Rotation of part 2: ax,ay,az,angle_deg (default: none)");
  cmd->add_option("--slice", opt->slice, "Slice of translations for the PNG: x=V, y=V or z=V");
  cmd->add_option("--png", opt->png, "Write a slice as a PNG");
  cmd->add_option("--vti", opt->vti, "Write the whole map as VTK image data");
  cmd->add_option("--modes", opt->modes, "Low-pass: keep about this many modes (default: all)");
  cmd->add_option("--pixels", opt->pixels, "Pixels per translation step in the PNG (default: 480 pixels or more)")
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--device", opt->device, "OpenCL device (see `snapfit devices`)");
  cmd->callback([opt] { run_map(*opt); });
}

}  // namespace snapfit::cli
