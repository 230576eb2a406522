// `snapfit scene-check SCENE`: parse and validate a scene, build both parts, and say
// what the engine will compute for it. `snapfit scene-check --fields` prints the scene
// format's field tables, as docs/scenes.md holds them.
#include <iostream>

#include "cli/commands.h"
#include "snapfit/inspect.h"

namespace snapfit::cli {

namespace {

// Every section's table between the markers docs/scenes.md keeps them in.
void print_field_tables() {
  for (const std::string& section : scene_field_sections())
    std::cout << "<!-- scene fields: " << section << " -->\n"
              << scene_fields_markdown(section) << "<!-- end scene fields -->\n\n";
}

}  // namespace

void add_scene_check_command(CLI::App& app) {
  auto file = std::make_shared<std::string>();
  auto fields = std::make_shared<bool>(false);
  CLI::App* cmd =
      app.add_subcommand("scene-check", "Validate a scene file, build its parts and print the compute plan");
  cmd->add_option("scene", *file, "Scene file (JSON, see docs/scenes.md)");
  cmd->add_flag("--fields", *fields,
                "print the scene format's fields (type, default, allowed values, meaning) as docs/scenes.md's tables");
  cmd->callback([file, fields] {
    if (*fields) return print_field_tables();
    if (file->empty()) throw CLI::RequiredError("scene");
    const Scene scene = load_scene(*file);
    std::cout << scene_summary_text(scene, check_scene(scene));
    std::cout << "scene is valid\n";
  });
}

}  // namespace snapfit::cli
