#pragma once
// The subcommands of the `snapfit` tool; each file cli/cmd_*.cpp adds one.
#include <CLI/CLI.hpp>

namespace snapfit::cli {

void add_devices_command(CLI::App& app);
void add_mesh_info_command(CLI::App& app);
void add_scene_check_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_fields_command(CLI::App& app);
void add_query_command(CLI::App& app);
void add_map_command(CLI::App& app);
void add_search_command(CLI::App& app);
void add_tune_command(CLI::App& app);
void add_accuracy_command(CLI::App& app);
void add_spheres_command(CLI::App& app);
void add_serve_command(CLI::App& app);

}  // namespace snapfit::cli
