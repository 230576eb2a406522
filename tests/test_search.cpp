// snapfit::search (jobs/search.cpp): on the shipped peg and hole at a coarse spacing,
// the maps' minima against queries of the same interpolated spectrum at every mode, and
// a process other than 0 against process 0's own maps of the same rotations.
#include <cmath>
#include <doctest/doctest.h>

#include "engine/query/query_engine.h"
#include "jobs/search_codec.h"
#include "pipeline/assembly_access.h"
#include "pipeline/assembly_pair.h"
#include "snapfit/assembly.h"
#include "snapfit/error.h"
#include "snapfit/search.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

// The shipped peg and hole with 0.5 mm clearance at twice its spacing (small maps).
Scene coarse_peg_and_hole() {
  Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/peg_hole_clearance_0p5.json");
  scene.grid.spacing = 1.2;
  scene.grid.resolution.reset();
  return scene;
}

SearchRequest small_request() {
  SearchRequest request;
  request.rotations = 16;
  request.top = 4;
  request.refine_queries = 10;
  request.map_fft = "clfft";
  return request;
}

// Process `rank` of `size`, given process 0's spectra: records what it sends.
class OtherProcess final : public SearchExchange {
 public:
  OtherProcess(int rank, int size, std::vector<double> spectra) : rank_(rank), size_(size), spectra_(spectra) {}
  int rank() const override { return rank_; }
  int size() const override { return size_; }
  int local_rank() const override { return 0; }
  void checkpoint(const std::string& error) override {
    if (!error.empty()) throw Error(error);
  }
  std::vector<double> gather(const std::vector<double>& mine) override {
    gathered.push_back(mine);
    return {};
  }
  void broadcast(std::vector<double>& values) override { values = spectra_; }
  std::vector<std::vector<double>> gathered;

 private:
  int rank_, size_;
  std::vector<double> spectra_;
};

}  // namespace

TEST_CASE("search: the maps' minima are the energies a query gives there, best first, each refined") {
  const Scene scene = coarse_peg_and_hole();
  const SearchResult r = search(scene, small_request());
  REQUIRE(r.top.size() == 4);
  CHECK(r.plan.rotations == r.rotations.size());
  CHECK(r.best_energy.size() == r.rotations.size());
  CHECK(r.process_rotations == std::vector<std::size_t>{r.rotations.size()});
  CHECK(r.map_fft == "clfft");

  // The same trilinear interpolation of part 2's spectrum at every mode, pose by pose.
  Scene turning = scene;
  turning.motion = Motion::six_dof;
  const Assembly assembly(turning);
  QueryVariant variant = assembly.query_variant(Interpolation::trilinear);
  variant.force = variant.torque = false;
  auto engine = assembly.make_query_engine(variant);
  engine->set_modes(engine->max_modes());
  for (std::size_t k = 0; k < r.top.size(); ++k) {
    const FoundPose& found = r.top[k];
    CAPTURE(k);
    if (k > 0) CHECK(found.energy >= r.top[k - 1].energy);
    CHECK(found.energy >= r.best_energy[found.rotation]);
    const double queried = engine->query(found.pose).energy;
    CHECK(std::abs(found.energy - queried) <= 1e-3 * std::abs(queried) + 1e-6);
    CHECK(found.refined.error.empty());
  }
  CHECK(r.top[0].energy == doctest::Approx(r.best_energy[r.top[0].rotation]));
  // With the scene's rigid contact the refinement rests on the rendered potential
  // (tests/test_search_cli.cpp checks where: at the fit).
  CHECK(r.top[0].refined.rendered);
  CHECK(r.top[0].refined.newton_steps > 0);
  CHECK(r.top[0].refined.modes == 65536);
}

TEST_CASE("search: process 1 of 3 maps rotations 1, 4, 7, ... with the minima process 0 finds for them") {
  const Scene scene = coarse_peg_and_hole();
  const SearchRequest request = small_request();
  const SearchResult alone = search(scene, request);
  Scene turning = scene;
  turning.motion = Motion::six_dof;
  const Assembly assembly(turning);
  OtherProcess other(1, 3, encode_spectra(AssemblyAccess::pair(assembly).spectra));
  const SearchResult result = search(scene, request, other);
  CHECK(result.top.empty());
  CHECK(result.rotations.empty());
  REQUIRE(other.gathered.size() == 3);  // best energies, candidates, rate
  const std::vector<double>& best = other.gathered[0];
  std::size_t expected = 0;
  for (std::size_t r = 1; r < alone.rotations.size(); r += 3) ++expected;
  REQUIRE(best.size() == 2 * expected);
  for (std::size_t i = 0; i < expected; ++i) {
    CHECK(best[2 * i] == double(1 + 3 * i));
    CHECK(best[2 * i + 1] == doctest::Approx(alone.best_energy[1 + 3 * i]).epsilon(1e-6));
  }
  CHECK(other.gathered[2].at(0) == double(expected));
}

TEST_CASE("search: a bad request or spectra that do not decode is an error that names it") {
  const Scene scene = coarse_peg_and_hole();
  SearchRequest both = small_request();
  both.step_deg = 30;
  CHECK(test::error_of([&] { search(scene, both); }).find("give one of them") != std::string::npos);
  SearchRequest unknown = small_request();
  unknown.map_fft = "cufft";
  CHECK(test::error_of([&] { search(scene, unknown); }).find("cufft") != std::string::npos);
  OtherProcess truncated(1, 2, {140, 140, 140, 0.6});
  CHECK(test::error_of([&] { search(scene, small_request(), truncated); }).find("truncated") != std::string::npos);
}

TEST_CASE("search codec: spectra and candidates round-trip, a foreign rotation index is refused") {
  PairSpectra s;
  s.dims = {4, 3, 2};
  s.spacing = 0.5;
  s.length = Eigen::Vector3d(2, 1.5, 1);
  s.part1.centre = Eigen::Vector3d(1, 2, 3);
  s.part1.half_extent = Eigen::Vector3d(4, 5, 6);
  s.part1.sample_parity = -1;
  s.part1.rho = {Complex(1, 2), Complex(-3, 0.25f)};
  s.part2.rho = {Complex(7, -8)};
  s.part2.sample_parity = 1;
  const PairSpectra back = decode_spectra(encode_spectra(s));
  CHECK(back.dims == s.dims);
  CHECK(back.spacing == s.spacing);
  CHECK(back.length == s.length);
  CHECK(back.part1.centre == s.part1.centre);
  CHECK(back.part1.half_extent == s.part1.half_extent);
  CHECK(back.part1.sample_parity == -1);
  CHECK(back.part1.rho == s.part1.rho);
  CHECK(back.part2.rho == s.part2.rho);
  std::vector<double> cut = encode_spectra(s);
  cut.pop_back();
  CHECK_THROWS_AS(decode_spectra(cut), Error);

  const std::vector<Eigen::Quaterniond> rotations = {Eigen::Quaterniond::Identity(),
                                                     Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitX()))};
  PoseCandidate c;
  c.rotation = 1;
  c.cell = 17;
  c.energy = -2.5;
  c.pose.translation = Eigen::Vector3d(0.1, 0.2, 0.3);
  const std::vector<PoseCandidate> decoded = decode_candidates(encode_candidates({c}), rotations);
  REQUIRE(decoded.size() == 1);
  CHECK(decoded[0].rotation == 1);
  CHECK(decoded[0].cell == 17);
  CHECK(decoded[0].energy == -2.5);
  CHECK(decoded[0].pose.translation == c.pose.translation);
  CHECK(decoded[0].pose.rotation.isApprox(rotations[1]));
  c.rotation = 2;
  CHECK(test::error_of([&] { decode_candidates(encode_candidates({c}), rotations); }).find("rotation 2") !=
        std::string::npos);
}
