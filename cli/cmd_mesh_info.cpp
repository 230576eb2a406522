// `snapfit mesh-info FILE`: load a mesh through Assimp and print its validation report.
#include <iostream>

#include "cli/commands.h"
#include "io/mesh_load.h"
#include "mesh/mesh_report.h"
#include "snapfit/error.h"

namespace snapfit::cli {
namespace {

struct MeshInfoOptions {
  std::string file;
  double scale = 1.0;
  bool json = false;
};

}  // namespace

void add_mesh_info_command(CLI::App& app) {
  auto opt = std::make_shared<MeshInfoOptions>();
  CLI::App* cmd =
      app.add_subcommand("mesh-info", "Load a mesh (any format Assimp reads) and print a validation report");
  cmd->add_option("file", opt->file, "Mesh file (STL, OBJ, PLY, glTF, OFF, ...)")->required();
  cmd->add_option("--scale", opt->scale, "Multiply every coordinate by this (file units -> your units)");
  cmd->add_flag("--json", opt->json, "Print the report as one JSON object");
  cmd->callback([opt] {
    const MeshReport report = validate_mesh(load_mesh(opt->file, opt->scale));
    if (opt->json) {
      std::cout << mesh_report_json(report) << "\n";
    } else {
      std::cout << opt->file << "\n" << format_mesh_report(report);
    }
  });
}

}  // namespace snapfit::cli
