// The rigid contact's disk cache (scheduler/haptics/contact_cache.h) on the shipped peg and
// hole: a model read back from the cache renders exactly the wrench, energy and stiffness
// of the one built; a corrupt or truncated entry is rebuilt, never used; the key changes
// with either mesh and with the spacings.
#include <chrono>
#include <doctest/doctest.h>
#include <filesystem>

#include "pipeline/assembly_pair.h"
#include "scheduler/haptics/contact_cache.h"
#include "scheduler/haptics/rigid_contact.h"
#include "tests/test_support.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

Pose at(double x, double y, double z, double tilt_deg) {
  Pose p;
  p.translation = Eigen::Vector3d(x, y, z);
  p.rotation = Eigen::Quaterniond(Eigen::AngleAxisd(tilt_deg * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized()));
  return p;
}

void check_same(const RigidContactModel& a, const RigidContactModel& b) {
  std::size_t touching = 0;
  for (const Pose& pose : {at(0, 0, -20.2, 0), at(0.3, 0, -10, 1.5), at(0.8, -0.4, -0.3, 3), at(0, 0, -19, 0.5)}) {
    const ContactWrench x = contact_wrench(a, pose), y = contact_wrench(b, pose);
    CHECK(x.points == y.points);
    CHECK(x.energy_j == y.energy_j);
    CHECK(x.wrench.force == y.wrench.force);
    CHECK(x.wrench.torque == y.wrench.torque);
    CHECK(x.stiffness == y.stiffness);
    touching += x.points;
  }
  CHECK(touching > 0);  // the poses include contact
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

TEST_CASE("contact cache: a cached model renders what the built one does, a corrupt entry is rebuilt") {
  test::CacheDirScope cache;
  const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  const AssemblyPair pair = prepare_assembly_pair(scene);
  const Mesh& m1 = pair.part(1).mesh;
  const Mesh& m2 = pair.part(2).mesh;
  const double h = pair.grids.spacing;

  auto start = std::chrono::steady_clock::now();
  const auto built = rigid_contact_for(scene, m1, m2, h);
  const double build_s = seconds_since(start);
  REQUIRE(built);
  const std::string key = contact_cache_key(m1, m2, h, h / 3, 2 * h);
  const std::string path = contact_cache_path(key);
  REQUIRE(fs::exists(path));
  start = std::chrono::steady_clock::now();
  const auto cached = rigid_contact_for(scene, m1, m2, h);
  MESSAGE("built in " << build_s << " s, read back in " << seconds_since(start) << " s (" << fs::file_size(path)
                      << " bytes)");
  REQUIRE(cached);
  CHECK(cached->skin == built->skin);
  CHECK(cached->pressure_stiffness == built->pressure_stiffness);
  CHECK(cached->part2_samples.points.size() == built->part2_samples.points.size());
  check_same(*built, *cached);

  // Another stiffness uses the same geometry: not part of the key.
  Scene stiffer = scene;
  stiffer.haptics.contact_stiffness_n_per_mm3 *= 2;
  const auto other = rigid_contact_for(stiffer, m1, m2, h);
  REQUIRE(other);
  CHECK(other->pressure_stiffness == doctest::Approx(2 * built->pressure_stiffness));

  // Truncated, and one flipped byte in the payload: never used, rebuilt and rewritten.
  std::vector<char> bytes = test::read_bytes(path);
  test::write_bytes(path, std::vector<char>(bytes.begin(), bytes.begin() + bytes.size() / 2));
  CHECK_FALSE(load_cached_contact(key).has_value());
  bytes[bytes.size() - 100] ^= 0x5a;
  test::write_bytes(path, bytes);
  CHECK_FALSE(load_cached_contact(key).has_value());
  const auto rebuilt = rigid_contact_for(scene, m1, m2, h);
  REQUIRE(rebuilt);
  check_same(*built, *rebuilt);
  CHECK(load_cached_contact(key).has_value());
}

TEST_CASE("contact cache: the key changes with either mesh and with the spacings") {
  const Scene scene = load_scene(std::string(SNAPFIT_SOURCE_DIR) + "/scenes/default.json");
  const AssemblyPair pair = prepare_assembly_pair(scene);
  const Mesh& m1 = pair.part(1).mesh;
  Mesh moved = pair.part(2).mesh;
  moved.vertices[0].x() += 1e-9;
  const std::string key = contact_cache_key(m1, pair.part(2).mesh, 0.6, 0.2, 1.2);
  CHECK(contact_cache_key(m1, moved, 0.6, 0.2, 1.2) != key);
  CHECK(contact_cache_key(pair.part(2).mesh, m1, 0.6, 0.2, 1.2) != key);
  CHECK(contact_cache_key(m1, pair.part(2).mesh, 0.5, 0.2, 1.2) != key);
  CHECK(contact_cache_key(m1, pair.part(2).mesh, 0.6, 0.25, 1.2) != key);
  CHECK(contact_cache_key(m1, pair.part(2).mesh, 0.6, 0.2, 1.0) != key);
  CHECK(contact_cache_key(m1, pair.part(2).mesh, 0.6, 0.2, 1.2) == key);
}
