// `snapfit mesh-info FILE`: load a mesh through Assimp, or tessellate a STEP or IGES
// file through OpenCASCADE, and print its validation report (and the CAD facts).
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "cli/commands.h"
#include "snapfit/error.h"
#include "snapfit/inspect.h"

namespace snapfit::cli {
namespace {

// Points of the grid over the solid that the default deflection is tied to when neither
// --deflection nor --spacing is given: about the shipped scenes' grids.
constexpr int kDefaultResolution = 64;

struct MeshInfoOptions {
  std::string file;
  double scale = 1.0;
  bool json = false;
  // STEP and IGES only
  std::string units = "mm";
  std::string solid;
  std::optional<double> deflection;
  std::optional<double> spacing;
  int resolution = kDefaultResolution;
  double angular_deflection_deg = kDefaultAngularDeflectionDeg;
};

void print(const MeshInfoOptions& opt, const MeshFileReport& report) {
  if (opt.json) {
    nlohmann::json j = nlohmann::json::parse(mesh_report_json(report.mesh));
    if (report.cad) j["cad"] = nlohmann::json::parse(cad_facts_json(*report.cad));
    std::cout << j.dump() << "\n";
  } else {
    std::cout << opt.file << "\n" << format_mesh_report(report.mesh);
    if (report.cad) std::cout << format_cad_facts(*report.cad);
  }
}

MeshFileRequest mesh_file_request(const MeshInfoOptions& opt) {
  MeshFileRequest request;
  request.file = opt.file;
  request.scale = opt.scale;
  if (is_cad_file(opt.file)) {  // the units matter to STEP and IGES files alone
    try {
      request.metres_per_unit = metres_per_unit(opt.units);
      request.units = opt.units;
    } catch (const Error& e) {
      throw Error(std::string("--units: ") + e.what());
    }
  }
  request.solid = opt.solid;
  request.deflection = opt.deflection;
  request.spacing = opt.spacing;
  request.resolution = opt.resolution;
  request.angular_deflection_deg = opt.angular_deflection_deg;
  return request;
}

}  // namespace

void add_mesh_info_command(CLI::App& app) {
  auto opt = std::make_shared<MeshInfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "mesh-info", "Load a mesh (any format Assimp reads, or STEP/IGES through OpenCASCADE) and print a report");
  cmd->add_option("file", opt->file, "Mesh file (STL, OBJ, PLY, glTF, OFF, ..., STEP, IGES)")->required();
  cmd->add_option("--scale", opt->scale, "Multiply every coordinate by this (file units -> your units)");
  cmd->add_flag("--json", opt->json, "Print the report as one JSON object");
  const char* group = "STEP and IGES files";
  cmd->add_option("--units", opt->units, "Length unit to report in (the file's unit is converted): um mm cm m km in")
      ->group(group);
  cmd->add_option("--solid", opt->solid, "The solid to tessellate, for a file with several")->group(group);
  cmd->add_option("--deflection", opt->deflection, "Linear deflection in --units (default: the grid spacing / 40)")
      ->group(group);
  cmd->add_option("--spacing", opt->spacing, "Grid spacing the default deflection is tied to, in --units")
      ->group(group);
  cmd->add_option("--resolution", opt->resolution,
                  "Without --spacing: the spacing of a grid of this many points along the solid's longest side")
      ->group(group);
  cmd->add_option("--angular-deflection", opt->angular_deflection_deg, "Angular deflection in degrees")->group(group);
  cmd->callback([opt] { print(*opt, inspect_mesh_file(mesh_file_request(*opt))); });
}

}  // namespace snapfit::cli
