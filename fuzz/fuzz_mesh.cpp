// libFuzzer target: the mesh loader (io/mesh_load.h load_mesh) on arbitrary bytes.
// The first byte picks the file extension (Assimp chooses its importer by extension
// and content); the rest is written to a temporary file and loaded. Every input must
// either load a finite mesh with valid indices or throw snapfit::Error.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <string>
#include <unistd.h>

#include "io/mesh_load.h"
#include "snapfit/error.h"

namespace {
const char* const kExtensions[] = {".stl", ".obj", ".ply", ".off", ".gltf", ".glb", ".3ds", ".dae", ".fbx", ".x"};
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const char* ext = kExtensions[data[0] % (sizeof kExtensions / sizeof *kExtensions)];
  const std::string path = "/tmp/snapfit-fuzz-mesh-" + std::to_string(::getpid()) + ext;
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return 0;
  std::fwrite(data + 1, 1, size - 1, f);
  std::fclose(f);
  try {
    const snapfit::Mesh mesh = snapfit::load_mesh(path);
    for (const auto& v : mesh.vertices)
      if (!v.allFinite()) __builtin_trap();
    for (const auto& t : mesh.triangles)
      for (int c = 0; c < 3; ++c)
        if (t[c] < 0 || t[c] >= static_cast<int>(mesh.vertices.size())) __builtin_trap();
  } catch (const snapfit::Error&) {
  }
  std::remove(path.c_str());
  return 0;
}
