// Writes the B-rep twins of a scene's procedural peg and hole block as STEP files:
//   make_cad_parts SCENE OUT_DIR
// gives OUT_DIR/<type>.step for part 1 and part 2, each solid named as its part; the
// peg's file declares inches, the hole block's millimetres (the reader converts both).
// scenes/parts/ holds what `make_cad_parts scenes/default.json scenes/parts` writes.
#include <filesystem>
#include <iostream>

#include "snapfit/error.h"
#include "snapfit/scene.h"
#include "tests/cad_fixtures.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_cad_parts SCENE OUT_DIR\n";
    return 2;
  }
  try {
    const snapfit::Scene scene = snapfit::load_scene(argv[1]);
    std::filesystem::create_directories(argv[2]);
    for (const snapfit::PartSpec* part : {&scene.part1, &scene.part2}) {
      if (!part->procedural) throw snapfit::Error("part '" + part->name + "' is not procedural");
      const std::string type = part->procedural->type;
      const std::string file = (std::filesystem::path(argv[2]) / (type + ".step")).string();
      snapfit::test::write_cad_part(file, *part->procedural, type == "peg" ? "INCH" : "MM", part->name);
      std::cout << file << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "make_cad_parts: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
