// A scene part's spectrum from its spherical decomposition ("descriptor": {"source":
// "spheres"}, pipeline/sphere_spectra.h): the scene fields and their errors, the cache
// key, the zero mode against the solid's volume, and scene-check and query on such a scene.
#include <cmath>
#include <doctest/doctest.h>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "mesh/mesh_mass_properties.h"
#include "pipeline/assembly_pair.h"
#include "pipeline/spectra_cache.h"
#include "pipeline/sphere_spectra.h"
#include "tests/test_engine_support.h"

using namespace snapfit;

namespace {

std::string collision_scene_text() {
  std::ifstream in(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/collision_only.json");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// collision_only.json with `descriptor` (a JSON object) added to part 1.
Scene with_part1_descriptor(const std::string& descriptor, const std::string& kind = "indicator") {
  nlohmann::json j = nlohmann::json::parse(collision_scene_text());
  j["part1"]["descriptor"] = nlohmann::json::parse(descriptor);
  j["descriptor"] = {{"kind", kind}};
  j["grid"]["spacing"] = 2.0;  // a coarse lattice keeps the NDFT and the NUFFT's FFTs small
  return parse_scene(j.dump(), std::string(SNAPFIT_SOURCE_DIR) + "/scenes/x.json");
}

}  // namespace

TEST_CASE("sphere spectra: the scene's part descriptor fields and their errors") {
  const Scene s = with_part1_descriptor(R"({"source": "spheres", "tolerance": 0.8, "protrusion": 0.5})");
  CHECK(s.part1.descriptor.source == SpectrumSource::spheres);
  CHECK(*s.part1.descriptor.tolerance == 0.8);
  CHECK(s.part1.descriptor.protrusion == 0.5);
  CHECK(s.part2.descriptor.source == SpectrumSource::grid);
  const Scene again = parse_scene(scene_to_json(s), s.source_path);
  CHECK(again.part1.descriptor.source == SpectrumSource::spheres);
  CHECK(*again.part1.descriptor.tolerance == 0.8);
  CHECK(again.part1.descriptor.method == "auto");
  auto error = [](const std::string& descriptor, const std::string& kind = "indicator") {
    return test::error_of([&] { with_part1_descriptor(descriptor, kind); });
  };
  CHECK(error(R"({"source": "balls"})").find("part1.descriptor.source: unknown source 'balls'") != std::string::npos);
  CHECK(error(R"({"source": "spheres", "protrusion": 2})").find("part1.descriptor.protrusion: must be in [0, 1]") !=
        std::string::npos);
  CHECK(error(R"({"source": "spheres", "tolerance": -1})").find("part1.descriptor.tolerance") != std::string::npos);
  CHECK(error(R"({"source": "spheres", "method": "fast"})").find("unknown method 'fast'") != std::string::npos);
  CHECK(error(R"({"source": "spheres", "nufft_tolerance": 0.5})").find("nufft_tolerance: must be in (0, 0.1]") !=
        std::string::npos);
  CHECK(error(R"({"source": "grid", "tolerance": 1})").find("only for source \"spheres\"") != std::string::npos);
  CHECK(error(R"({"source": "spheres", "radius": 1})").find("unknown field") != std::string::npos);
  CHECK(error(R"({"source": "spheres"})", "skeletal_density").find("gives the indicator descriptor only") !=
        std::string::npos);
  CHECK(error(R"("spheres")").find("part1.descriptor: expected an object") != std::string::npos);
}

// (The NUFFT against the direct sum: tests/test_ball_spectrum.cpp.)
TEST_CASE("sphere spectra: the cache key names the source, the zero mode is the solid's volume") {
  const test::CacheDirScope cache;
  const Scene grid_scene = with_part1_descriptor(R"({"source": "grid"})");
  const Scene direct = with_part1_descriptor(R"({"source": "spheres", "tolerance": 2.5, "method": "direct"})");
  const Scene nufft = with_part1_descriptor(R"({"source": "spheres", "tolerance": 2.5, "method": "nufft"})");
  CHECK(spectrum_source_key(grid_scene.part1.descriptor, 0.6) == "grid");
  CHECK(spectrum_source_key(direct.part1.descriptor, 0.6) != spectrum_source_key(nufft.part1.descriptor, 0.6));
  const FftLibrary fft;
  PairOptions options;
  options.note = [](const std::string&) {};
  options.descriptors.program_cache = test::test_program_cache();
  const AssemblyPair g = build_assembly_pair(grid_scene, test::test_context(), fft, options);
  const AssemblyPair d = build_assembly_pair(direct, test::test_context(), fft, options);
  CHECK_FALSE(d.spectra_from_cache);  // the grid entry, same fields, is not reused
  REQUIRE(d.spectra.dims == g.spectra.dims);
  const double volume = std::abs(solid_moments(d.part(1).mesh).volume);
  // Samples i * density: the zero mode is i * integral = i |S| for the balls (by the weight).
  CHECK(d.spectra.part1.rho[0].imag() == doctest::Approx(volume).epsilon(1e-4));
  CHECK(std::abs(d.spectra.part1.rho[0].real()) < 1e-3 * volume);
  CHECK(d.spectra.part2.rho == g.spectra.part2.rho);  // part 2 stays on the grid
  CHECK(d.spectra.part1.sample_parity == -1);
  const AssemblyPair again = build_assembly_pair(direct, test::test_context(), fft, options);
  CHECK(again.spectra_from_cache);
  CHECK(again.spectra.part1.rho == d.spectra.part1.rho);
}

TEST_CASE("sphere spectra: scene-check and query on a scene with two spheres parts") {
  const test::CacheDirScope cache;
  const test::TempDir dir;
  nlohmann::json j = nlohmann::json::parse(collision_scene_text());
  j["part1"]["descriptor"] = {{"source", "spheres"}, {"tolerance", 2.5}};
  j["part2"]["descriptor"] = {{"source", "spheres"}, {"tolerance", 2.5}};
  j["part1"]["procedural"]["segments"] = 32;
  j["part2"]["procedural"]["segments"] = 32;
  j["grid"]["spacing"] = 2.0;
  const std::string scene = dir.file("spheres.json");
  test::write_text(scene, j.dump());
  const std::string cli = std::string(SNAPFIT_CLI_PATH);
  const test::Command check = test::run_command(cli + " scene-check " + scene);
  INFO(check.output);
  CHECK(check.status == 0);
  // The plan names both parts' balls and recommends the grid path for each.
  CHECK(check.output.find("part 1's spectrum: seed 001's balls (tolerance 2.5") != std::string::npos);
  CHECK(check.output.find("part 2's spectrum: seed 001's balls (tolerance 2.5") != std::string::npos);
  CHECK(check.output.find("warning: part 2 takes its spectrum from balls: \"source\": \"grid\" is recommended") !=
        std::string::npos);
  const test::Command query = test::run_command(cli + " query " + scene + " --pose 0,0,8 --pose 12,0,-5", false);
  INFO(query.output);
  REQUIRE(query.status == 0);
  std::istringstream lines(query.output);
  std::string line;
  std::vector<double> energies;
  while (std::getline(lines, line))
    if (!line.empty() && line[0] == '{') energies.push_back(nlohmann::json::parse(line)["energy"].get<double>());
  REQUIRE(energies.size() == 2);
  // 8 mm above the block: no overlap; 12 mm off the hole's axis and 5 mm down: the peg's
  // end overlaps the block's top (a few hundred mm^3).
  CHECK(std::abs(energies[1]) > 10 * std::abs(energies[0]));
}
