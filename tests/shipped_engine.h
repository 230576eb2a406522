#pragma once
// A shipped scene's pair (fields and spectra, built quietly through the caches) and the
// query engine of its variant, as `snapfit run` prepares them for the loop: for the
// tests that drive the real engine on the shipped parts.
#include <memory>
#include <string>

#include "engine/query/query_engine.h"
#include "pipeline/assembly_pair.h"
#include "tests/test_engine_support.h"

namespace snapfit::test {

struct ShippedEngine {
  AssemblyPair pair;  // pair.scene is the scene
  std::unique_ptr<QueryEngine> engine;
};

inline Scene shipped_scene(const std::string& file) {
  return load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/" + file);
}

inline ShippedEngine shipped_engine(const Scene& scene) {
  const FftLibrary fft;
  PairOptions options;
  options.note = [](const std::string&) {};
  ShippedEngine s;
  s.pair = build_assembly_pair(scene, test_context(), fft, options);
  s.engine = make_query_engine(test_context(), s.pair.spectra, query_variant_for(scene), test_program_cache());
  return s;
}

}  // namespace snapfit::test
