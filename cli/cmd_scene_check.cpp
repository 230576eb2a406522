// `snapfit scene-check SCENE`: parse and validate a scene, build both parts, and say
// what the engine will compute for it.
#include <iostream>

#include "cli/commands.h"
#include "snapfit/inspect.h"

namespace snapfit::cli {

void add_scene_check_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("scene-check", "Validate a scene file, build its parts and print the compute plan");
  cmd->add_option("scene", *file, "Scene file (JSON, see docs/scenes.md)")->required();
  cmd->callback([file] {
    const Scene scene = load_scene(*file);
    std::cout << scene_summary_text(scene, check_scene(scene));
    std::cout << "scene is valid\n";
  });
}

}  // namespace snapfit::cli
