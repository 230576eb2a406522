// libFuzzer target: the scene loader (snapfit/scene.h parse_scene) on arbitrary bytes.
// Every input must either parse or throw snapfit::Error; any other exception, a crash,
// an ASan report or a hang is a bug (see fuzz/README.md).
#include <cstddef>
#include <cstdint>
#include <string>

#include "snapfit/error.h"
#include "snapfit/scene.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const snapfit::Scene scene = snapfit::parse_scene(text, "/nonexistent/fuzz.json");
    // A scene that parses must round-trip through its own writer.
    const snapfit::Scene again = snapfit::parse_scene(snapfit::scene_to_json(scene), "/nonexistent/fuzz.json");
    if (snapfit::scene_to_json(again) != snapfit::scene_to_json(scene)) __builtin_trap();
  } catch (const snapfit::Error&) {
  }
  return 0;
}
