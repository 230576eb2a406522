// Versioned, checksummed, atomically written cache files (io/cache_file.h).
#include <doctest/doctest.h>
#include <filesystem>

#include "io/cache_file.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {
const std::string kPayload = "the quick brown fox jumps over the lazy dog";

void write_entry(const std::string& path) {
  write_cache_file(path, "test-kind", 3, "key=a|b", kPayload.data(), kPayload.size());
}
}  // namespace

TEST_CASE("cache file: round trip, and no temporary file is left behind") {
  test::TempDir dir;
  const std::string path = dir.file("nested/folder/entry.bin");
  write_entry(path);
  const CacheRead r = read_cache_file(path, "test-kind", 3, "key=a|b");
  REQUIRE(r.status == CacheStatus::hit);
  CHECK(std::string(r.payload.begin(), r.payload.end()) == kPayload);
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path)) files += e.is_regular_file();
  CHECK(files == 1);
}

TEST_CASE("cache file: missing, stale kind, version and key") {
  test::TempDir dir;
  const std::string path = dir.file("entry.bin");
  CHECK(read_cache_file(path, "test-kind", 3, "key=a|b").status == CacheStatus::missing);
  write_entry(path);
  CHECK(read_cache_file(path, "other-kind", 3, "key=a|b").status == CacheStatus::stale);
  CHECK(read_cache_file(path, "test-kind", 4, "key=a|b").status == CacheStatus::stale);
  const CacheRead r = read_cache_file(path, "test-kind", 3, "key=a|c");
  CHECK(r.status == CacheStatus::stale);
  CHECK(r.reason.find("key") != std::string::npos);
}

TEST_CASE("cache file: truncation, flipped bits and foreign files are corrupt") {
  test::TempDir dir;
  const std::string path = dir.file("entry.bin");
  write_entry(path);
  const std::vector<char> good = test::read_bytes(path);

  SUBCASE("truncated payload") {
    test::write_bytes(path, std::vector<char>(good.begin(), good.end() - 5));
    CHECK(read_cache_file(path, "test-kind", 3, "key=a|b").status == CacheStatus::corrupt);
  }
  SUBCASE("truncated header") {
    test::write_bytes(path, std::vector<char>(good.begin(), good.begin() + 12));
    CHECK(read_cache_file(path, "test-kind", 3, "key=a|b").status == CacheStatus::corrupt);
  }
  SUBCASE("one payload bit flipped") {
    std::vector<char> bad = good;
    bad[bad.size() - 3] ^= 0x10;
    test::write_bytes(path, bad);
    const CacheRead r = read_cache_file(path, "test-kind", 3, "key=a|b");
    CHECK(r.status == CacheStatus::corrupt);
    CHECK(r.reason.find("checksum") != std::string::npos);
  }
  SUBCASE("not a cache file") {
    test::write_text(path, "hello");
    CHECK(read_cache_file(path, "test-kind", 3, "key=a|b").status == CacheStatus::corrupt);
  }
  SUBCASE("empty file") {
    test::write_text(path, "");
    CHECK(read_cache_file(path, "test-kind", 3, "key=a|b").status == CacheStatus::corrupt);
  }
}

TEST_CASE("cache file: an unwritable location is an error naming the path, leaving nothing behind") {
  test::TempDir dir;
  // A regular file where a folder should be: create_directories must fail.
  test::write_text(dir.file("blocker"), "x");
  const std::string path = dir.file("blocker/sub/entry.bin");
  CHECK_THROWS_WITH_AS(write_entry(path), doctest::Contains("blocker"), Error);
  int files = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir.path)) files += e.is_regular_file();
  CHECK(files == 1);
}

TEST_CASE("cache file: rewriting replaces the old entry whole") {
  test::TempDir dir;
  const std::string path = dir.file("entry.bin");
  write_entry(path);
  const std::string other = "a different payload";
  write_cache_file(path, "test-kind", 3, "key=a|b", other.data(), other.size());
  const CacheRead r = read_cache_file(path, "test-kind", 3, "key=a|b");
  REQUIRE(r.status == CacheStatus::hit);
  CHECK(std::string(r.payload.begin(), r.payload.end()) == other);
}
