// Descriptor field cache (pipeline/field_cache.h) through pipeline/part_fields.h: miss then hit
// with bit-identical fields, a new key for every value-changing input, recovery from
// corrupt and truncated entries, an unwritable cache folder, and use_cache = false.
// The cache root comes from $SNAPFIT_CACHE_DIR (io/cache_file.h cache_root()), pointed
// at a temporary folder per test and restored afterwards.
#include <cstdlib>
#include <cstring>
#include <doctest/doctest.h>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/runtime/compute_context.h"
#include "engine/runtime/device.h"
#include "io/cache_file.h"
#include "mesh/procedural/procedural_parts.h"
#include "pipeline/field_cache.h"
#include "pipeline/part_fields.h"
#include "tests/test_engine_support.h"
#include "tests/test_support.h"

using namespace snapfit;
namespace fs = std::filesystem;

namespace {

const ComputeContext& context() { return test::test_context(); }

// Compiled programs live in their own folder (built once), apart from the field cache under test.
DescriptorOptions options() {
  DescriptorOptions o;
  o.program_cache = test::test_program_cache();
  return o;
}

Mesh small_peg() { return make_procedural_part({"peg", {{"radius", 1}, {"length", 2}, {"segments", 8}}, {}}); }

GridSpec coarse_grid(const Mesh& mesh, double spacing = 0.4) {
  GridParams params;
  params.padding = 0.5;
  return part_grid(mesh, params, spacing);
}

// Plain files in `folder` (none when it does not exist).
std::vector<fs::path> files_in(const fs::path& folder) {
  std::vector<fs::path> out;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) return out;
  for (const auto& entry : fs::directory_iterator(folder)) out.push_back(entry.path());
  return out;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0);
}

bool same_fields(const DescriptorFields& a, const DescriptorFields& b) {
  return same_bits(a.winding, b.winding) && same_bits(a.winding_bound, b.winding_bound) &&
         same_bits(a.signed_distance, b.signed_distance) && same_bits(a.skeletal_density, b.skeletal_density) &&
         same_bits(a.density_bound, b.density_bound);
}

// Collects cache notes.
struct Notes {
  std::vector<std::string> lines;
  std::function<void(const std::string&)> sink() {
    return [this](const std::string& m) { lines.push_back(m); };
  }
  bool any_contains(const std::string& text) const {
    for (const auto& l : lines)
      if (l.find(text) != std::string::npos) return true;
    return false;
  }
  std::string all() const {
    std::string s;
    for (const auto& l : lines) s += l + "\n";
    return s;
  }
};

PartFieldsResult fields_of(const Mesh& mesh, const GridSpec& grid, const DescriptorParams& params, Notes& notes,
                           bool use_cache = true) {
  return part_fields(context(), mesh, grid, params, options(), use_cache, notes.sink());
}

void check_complete(const PartFieldsResult& r, const GridSpec& grid) {
  CHECK(r.fields.winding.size() == grid.count());
  CHECK(r.fields.winding_bound.size() == grid.count());
  CHECK(r.fields.signed_distance.size() == grid.count());
  CHECK(r.fields.skeletal_density.size() == grid.count());
  CHECK(r.fields.density_bound.size() == grid.count());
}

}  // namespace

TEST_CASE("field cache: miss writes one entry, then hits with bit-identical fields") {
  test::CacheDirScope scope;
  REQUIRE(cache_root() == scope.dir.path.string());
  const Mesh mesh = small_peg();
  const GridSpec grid = coarse_grid(mesh);
  REQUIRE(grid.count() > 0);
  REQUIRE(grid.count() < 5000);
  const DescriptorParams params;  // skeletal density, tolerance 0.1
  Notes notes;

  const PartFieldsResult first = fields_of(mesh, grid, params, notes);
  CHECK_FALSE(first.from_cache);
  check_complete(first, grid);
  const auto written = files_in(scope.folder("fields"));
  REQUIRE(written.size() == 1);
  CHECK(written[0].extension() == ".bin");
  CHECK(written[0].string() == descriptor_cache_path(descriptor_cache_key(mesh, grid, params, options())));
  CHECK(fs::is_regular_file(written[0]));
  // Nothing else under the cache root (no temp files, no other folders).
  CHECK(files_in(scope.dir.path).size() == 1);

  const PartFieldsResult second = fields_of(mesh, grid, params, notes);
  CHECK(second.from_cache);
  CHECK(same_fields(first.fields, second.fields));
  CHECK(second.fields.grid.dims == grid.dims);
  CHECK(second.fields.grid.origin == grid.origin);
  CHECK(second.fields.grid.spacing == grid.spacing);
  CHECK(second.fields.params.sigma == params.sigma);
  CHECK(files_in(scope.folder("fields")).size() == 1);
  CHECK_MESSAGE(notes.lines.empty(), notes.all());

  // The affinity factors do not change the fields: still a hit, with the new params.
  DescriptorParams lambdas = params;
  lambdas.lambda_in = 7.0;
  const PartFieldsResult third = fields_of(mesh, grid, lambdas, notes);
  CHECK(third.from_cache);
  CHECK(third.fields.params.lambda_in == 7.0);
  CHECK(same_fields(first.fields, third.fields));
}

TEST_CASE("field cache: every value-changing input makes a new key") {
  test::CacheDirScope scope;
  const Mesh mesh = small_peg();
  const GridSpec grid = coarse_grid(mesh);
  const DescriptorParams params;
  Notes notes;
  const PartFieldsResult base = fields_of(mesh, grid, params, notes);
  REQUIRE_FALSE(base.from_cache);
  std::size_t entries = 1;

  auto expect_miss_then_hit = [&](const Mesh& m, const GridSpec& g, const DescriptorParams& p) {
    const PartFieldsResult miss = fields_of(m, g, p, notes);
    CHECK_FALSE(miss.from_cache);
    CHECK(files_in(scope.folder("fields")).size() == ++entries);
    const PartFieldsResult hit = fields_of(m, g, p, notes);
    CHECK(hit.from_cache);
    CHECK(same_fields(miss.fields, hit.fields));
    return miss;
  };

  {
    INFO("sigma");
    DescriptorParams p = params;
    p.sigma = 0.7;
    const PartFieldsResult r = expect_miss_then_hit(mesh, grid, p);
    CHECK_FALSE(same_bits(r.fields.skeletal_density, base.fields.skeletal_density));
  }
  {
    INFO("tolerance");
    DescriptorParams p = params;
    p.tolerance = 0.05;
    expect_miss_then_hit(mesh, grid, p);
  }
  {
    INFO("descriptor kind");
    DescriptorParams p = params;
    p.kind = DescriptorKind::indicator;
    const PartFieldsResult r = expect_miss_then_hit(mesh, grid, p);
    CHECK(r.fields.skeletal_density.empty());
    CHECK(r.fields.winding.size() == grid.count());
  }
  {
    INFO("mesh: one vertex moved");
    Mesh moved = mesh;
    moved.vertices[0] += Eigen::Vector3d(0.01, 0.0, 0.0);
    CHECK(descriptor_cache_key(moved, grid, params, options()) != descriptor_cache_key(mesh, grid, params, options()));
    expect_miss_then_hit(moved, grid, params);
  }
  {
    INFO("grid spacing");
    const GridSpec finer = coarse_grid(mesh, 0.45);
    REQUIRE(finer.spacing != grid.spacing);
    const PartFieldsResult r = expect_miss_then_hit(mesh, finer, params);
    CHECK(r.fields.winding.size() == finer.count());
  }
  // The original entry is still there and still a hit.
  const PartFieldsResult again = fields_of(mesh, grid, params, notes);
  CHECK(again.from_cache);
  CHECK(same_fields(base.fields, again.fields));
  CHECK_MESSAGE(notes.lines.empty(), notes.all());
}

TEST_CASE("field cache: a corrupt or truncated entry is noted and recomputed, then hits again") {
  test::CacheDirScope scope;
  const Mesh mesh = small_peg();
  const GridSpec grid = coarse_grid(mesh);
  const DescriptorParams params;
  Notes notes;
  const PartFieldsResult base = fields_of(mesh, grid, params, notes);
  REQUIRE_FALSE(base.from_cache);
  const std::string path = descriptor_cache_path(descriptor_cache_key(mesh, grid, params, options()));
  const std::vector<char> good = test::read_bytes(path);
  REQUIRE(good.size() > 4 * grid.count());

  SUBCASE("a flipped payload byte") {
    std::vector<char> bad = good;
    bad[bad.size() - 3 * grid.count() / 2] ^= 0x5a;  // inside the float data
    test::write_bytes(path, bad);
  }
  SUBCASE("a flipped byte in the payload header") {
    std::vector<char> bad = good;
    const std::size_t payload = 12 + 5 * 4 * grid.count();
    REQUIRE(bad.size() > payload);
    bad[bad.size() - payload] ^= 0x01;  // the point count
    test::write_bytes(path, bad);
  }
  SUBCASE("truncated in the payload") {
    test::write_bytes(path,
                      std::vector<char>(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(good.size() - 100)));
  }
  SUBCASE("truncated in the header") { test::write_bytes(path, std::vector<char>(good.begin(), good.begin() + 20)); }
  SUBCASE("empty file") { test::write_bytes(path, {}); }

  const PartFieldsResult recomputed = fields_of(mesh, grid, params, notes);
  CHECK_FALSE(recomputed.from_cache);
  CHECK_MESSAGE(notes.any_contains("corrupt"), notes.all());
  CHECK(same_fields(base.fields, recomputed.fields));
  CHECK(test::read_bytes(path) == good);  // rewritten in full
  notes.lines.clear();
  const PartFieldsResult hit = fields_of(mesh, grid, params, notes);
  CHECK(hit.from_cache);
  CHECK(same_fields(base.fields, hit.fields));
  CHECK_MESSAGE(notes.lines.empty(), notes.all());
  CHECK(files_in(scope.folder("fields")).size() == 1);
}

TEST_CASE("field cache: an unwritable cache folder is a note, the fields are still right") {
  test::CacheDirScope scope;
  const Mesh mesh = small_peg();
  const GridSpec grid = coarse_grid(mesh);
  const DescriptorParams params;
  Notes notes;
  const PartFieldsResult reference = fields_of(mesh, grid, params, notes, false);

  test::write_text(scope.folder("fields").string(), "a regular file where the fields folder should be");
  REQUIRE(fs::is_regular_file(scope.folder("fields")));
  const PartFieldsResult r = fields_of(mesh, grid, params, notes);
  CHECK_FALSE(r.from_cache);
  CHECK_MESSAGE(notes.any_contains("not cached"), notes.all());
  check_complete(r, grid);
  CHECK(same_fields(reference.fields, r.fields));
  CHECK(fs::is_regular_file(scope.folder("fields")));
  // Still no cache: the next call computes again (and notes again).
  notes.lines.clear();
  const PartFieldsResult again = fields_of(mesh, grid, params, notes);
  CHECK_FALSE(again.from_cache);
  CHECK(notes.any_contains("not cached"));
  CHECK(files_in(scope.dir.path).size() == 1);  // only the blocking file, no temp files
}

TEST_CASE("field cache: use_cache = false never reads or writes") {
  test::CacheDirScope scope;
  const Mesh mesh = small_peg();
  const GridSpec grid = coarse_grid(mesh);
  const DescriptorParams params;
  Notes notes;
  const PartFieldsResult a = fields_of(mesh, grid, params, notes, false);
  CHECK_FALSE(a.from_cache);
  check_complete(a, grid);
  CHECK(files_in(scope.dir.path).empty());
  // With an entry present, it is still not read.
  const PartFieldsResult cached = fields_of(mesh, grid, params, notes, true);
  CHECK_FALSE(cached.from_cache);
  REQUIRE(files_in(scope.folder("fields")).size() == 1);
  const auto path = files_in(scope.folder("fields"))[0];
  std::vector<char> bad = test::read_bytes(path.string());
  bad.back() ^= 0x77;
  test::write_bytes(path.string(), bad);
  const PartFieldsResult b = fields_of(mesh, grid, params, notes, false);
  CHECK_FALSE(b.from_cache);
  CHECK(same_fields(a.fields, b.fields));
  CHECK(test::read_bytes(path.string()) == bad);  // untouched
  CHECK_MESSAGE(notes.lines.empty(), notes.all());
}
