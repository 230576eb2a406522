// Writes the real-CAD pairs (tests/cad_pairs.h): each pair's two STEP files and its scene.
//   make_cad_pairs PARTS_DIR SCENES_DIR
// gives PARTS_DIR/<pair>_1.step, PARTS_DIR/<pair>_2.step and SCENES_DIR/<pair>.json, the
// scenes naming the parts by their path relative to SCENES_DIR. scenes/parts/cad/ and
// scenes/cad/ hold what `make_cad_pairs scenes/parts/cad scenes/cad` writes.
#include <filesystem>
#include <fstream>
#include <iostream>

#include "tests/cad_pairs.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: make_cad_pairs PARTS_DIR SCENES_DIR\n";
    return 2;
  }
  namespace fs = std::filesystem;
  try {
    fs::create_directories(argv[1]);
    fs::create_directories(argv[2]);
    const std::string relative =
        fs::relative(fs::absolute(argv[1]), fs::absolute(argv[2])).generic_string();
    for (const snapfit::test::CadPairInfo& pair : snapfit::test::cad_pairs()) {
      for (const std::string& file : snapfit::test::write_cad_pair(pair, argv[1])) std::cout << file << "\n";
      const std::string scene = (fs::path(argv[2]) / (pair.name + ".json")).string();
      std::ofstream(scene) << snapfit::test::cad_pair_scene(pair, relative);
      std::cout << scene << "\n";
    }
  } catch (const std::exception& e) {
    std::cerr << "make_cad_pairs: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
