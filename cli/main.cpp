// snapfit: haptic guidance for rigid-part assembly. One executable, one subcommand
// per task; `snapfit SUBCOMMAND --help` describes each.
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>

#include "cli/cli_terms.h"
#include "cli/commands.h"
#include "snapfit/devices.h"
#include "snapfit/error.h"

int main(int argc, char** argv) {
  // `snapfit run` tunes both PoCL CPU drivers and runs the loop on the one that suits
  // it; everything else still defaults to the multi-threaded one.
  snapfit::expose_pocl_caller_thread_driver();
  CLI::App app{"snapfit: geometric energy, force and torque between two rigid parts for haptic assembly"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("snapfit ") + SNAPFIT_VERSION);
  // Every option's --help shows its default (subcommands inherit this).
  app.option_defaults()->always_capture_default();
  snapfit::cli::add_devices_command(app);
  snapfit::cli::add_mesh_info_command(app);
  snapfit::cli::add_scene_check_command(app);
  snapfit::cli::add_fields_command(app);
  snapfit::cli::add_query_command(app);
  snapfit::cli::add_map_command(app);
  snapfit::cli::add_search_command(app);
  snapfit::cli::add_tune_command(app);
  snapfit::cli::add_accuracy_command(app);
  snapfit::cli::add_spheres_command(app);
  snapfit::cli::add_run_command(app);
  snapfit::cli::add_serve_command(app);
  // SNAPFIT_PARSE_ONLY=1 checks the command line (the subcommand, its options and their
  // values) and exits 0 without running it: scripts and the README's test check commands so.
  const char* parse_only = std::getenv("SNAPFIT_PARSE_ONLY");
  if (parse_only && std::strcmp(parse_only, "1") == 0)
    for (CLI::App* command : app.get_subcommands([](CLI::App*) { return true; })) command->callback(nullptr);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const snapfit::Error& e) {
    // The first line is the reason; anything after it (a compiler log, a device list) is detail.
    std::cerr << "snapfit: error: " << snapfit::cli::in_cli_terms(e.what()) << "\n";
    return 1;
  } catch (const std::exception& e) {
    std::cerr << "snapfit: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
