// VTK XML ImageData export (io/vti_export.h), read back by a small independent parser.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <doctest/doctest.h>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io/vti_export.h"
#include "snapfit/error.h"
#include "tests/test_support.h"

using namespace snapfit;

namespace {

// The value of attribute `name` in the first tag that starts with `tag_start` at or
// after `from`; "" when absent. Entities are decoded.
std::string attribute(const std::string& xml, const std::string& tag_start, const std::string& name,
                      std::size_t from = 0) {
  const std::size_t tag = xml.find(tag_start, from);
  if (tag == std::string::npos) return "";
  const std::size_t end = xml.find('>', tag);
  const std::size_t at = xml.find(" " + name + "=\"", tag);
  if (at == std::string::npos || at > end) return "";
  const std::size_t value = at + name.size() + 3;
  std::string raw = xml.substr(value, xml.find('"', value) - value);
  std::string out;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw[i] != '&') {
      out += raw[i];
      continue;
    }
    const std::size_t semi = raw.find(';', i);
    const std::string e = raw.substr(i, semi - i + 1);
    out += e == "&amp;" ? '&' : e == "&lt;" ? '<' : e == "&gt;" ? '>' : e == "&quot;" ? '"' : '\'';
    i = semi;
  }
  return out;
}

struct ReadArray {
  std::string name, type, format;
  int components = 0;
  std::uint64_t byte_count = 0;
  std::vector<float> values;
};

struct ReadVti {
  std::string header;  // the XML before the appended data
  std::vector<ReadArray> arrays;
  std::string tail;  // what follows the last block
};

std::uint64_t get_u64(const char* p) {
  std::uint64_t v = 0;
  for (int i = 7; i >= 0; --i) v = (v << 8) | static_cast<unsigned char>(p[i]);
  return v;
}

ReadVti read_vti(const std::string& path) {
  const std::vector<char> bytes = test::read_bytes(path);
  const std::string all(bytes.begin(), bytes.end());
  ReadVti r;
  const std::size_t appended = all.find("<AppendedData encoding=\"raw\">");
  REQUIRE(appended != std::string::npos);
  const std::size_t underscore = all.find('_', appended);
  REQUIRE(underscore != std::string::npos);
  const std::size_t data = underscore + 1;
  r.header = all.substr(0, appended);
  std::size_t end_of_blocks = data;
  for (std::size_t at = r.header.find("<DataArray "); at != std::string::npos;
       at = r.header.find("<DataArray ", at + 1)) {
    ReadArray a;
    a.name = attribute(r.header, "<DataArray ", "Name", at);
    a.type = attribute(r.header, "<DataArray ", "type", at);
    a.format = attribute(r.header, "<DataArray ", "format", at);
    a.components = std::atoi(attribute(r.header, "<DataArray ", "NumberOfComponents", at).c_str());
    const std::uint64_t offset = std::strtoull(attribute(r.header, "<DataArray ", "offset", at).c_str(), nullptr, 10);
    REQUIRE(data + offset + 8 <= all.size());
    a.byte_count = get_u64(all.data() + data + offset);
    REQUIRE(a.byte_count % 4 == 0);
    REQUIRE(data + offset + 8 + a.byte_count <= all.size());
    a.values.resize(a.byte_count / 4);
    for (std::size_t i = 0; i < a.values.size(); ++i) {
      const char* p = all.data() + data + offset + 8 + 4 * i;
      std::uint32_t bits = 0;
      for (int b = 3; b >= 0; --b) bits = (bits << 8) | static_cast<unsigned char>(p[b]);
      std::memcpy(&a.values[i], &bits, 4);
    }
    end_of_blocks = std::max<std::size_t>(end_of_blocks, data + offset + 8 + a.byte_count);
    r.arrays.push_back(a);
  }
  r.tail = all.substr(end_of_blocks);
  return r;
}

bool same_bits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

GridSpec small_grid() {
  GridSpec g;
  g.origin = Eigen::Vector3d(-1.25, 0.1, 3.0);
  g.spacing = 0.3;
  g.dims = Eigen::Vector3i(5, 4, 3);
  return g;
}

int files_in(const std::filesystem::path& dir) {
  int n = 0;
  for (const auto& e : std::filesystem::directory_iterator(dir)) n += e.is_regular_file();
  return n;
}

}  // namespace

TEST_CASE("vti export: header, offsets and every float round trip bit-exactly") {
  test::TempDir dir;
  const GridSpec g = small_grid();
  const std::size_t n = g.count();
  std::vector<float> scalar(n), vec(3 * n);
  for (std::size_t p = 0; p < n; ++p) scalar[p] = static_cast<float>(std::sin(0.7 * p) * 1e3);
  for (std::size_t p = 0; p < 3 * n; ++p) vec[p] = static_cast<float>(p) * 0.1f - 2.0f;
  // Values whose bits a text format or a careless copy would change.
  scalar[0] = -0.0f;
  scalar[1] = std::numeric_limits<float>::quiet_NaN();
  scalar[2] = std::numeric_limits<float>::infinity();
  scalar[3] = std::numeric_limits<float>::denorm_min();
  vec[5] = -std::numeric_limits<float>::max();

  const std::string path = dir.file("fields.vti");
  write_vti(path, g, {{"energy <E>", scalar.data(), 1}, {"force", vec.data(), 3}});
  CHECK(files_in(dir.path) == 1);  // no temporary left behind

  const ReadVti r = read_vti(path);
  CHECK(r.header.rfind("<?xml version=\"1.0\"?>", 0) == 0);
  CHECK(attribute(r.header, "<VTKFile ", "type") == "ImageData");
  CHECK(attribute(r.header, "<VTKFile ", "version") == "1.0");
  CHECK(attribute(r.header, "<VTKFile ", "byte_order") == "LittleEndian");
  CHECK(attribute(r.header, "<VTKFile ", "header_type") == "UInt64");
  CHECK(attribute(r.header, "<ImageData ", "WholeExtent") == "0 4 0 3 0 2");
  CHECK(attribute(r.header, "<Piece ", "Extent") == "0 4 0 3 0 2");
  // Origin and spacing are written with 17 digits: exact doubles back.
  double ox, oy, oz, sx, sy, sz;
  REQUIRE(std::sscanf(attribute(r.header, "<ImageData ", "Origin").c_str(), "%lf %lf %lf", &ox, &oy, &oz) == 3);
  REQUIRE(std::sscanf(attribute(r.header, "<ImageData ", "Spacing").c_str(), "%lf %lf %lf", &sx, &sy, &sz) == 3);
  CHECK(ox == g.origin.x());
  CHECK(oy == g.origin.y());
  CHECK(oz == g.origin.z());
  CHECK(sx == g.spacing);
  CHECK(sy == g.spacing);
  CHECK(sz == g.spacing);
  CHECK(attribute(r.header, "<PointData", "Scalars") == "energy <E>");
  CHECK(attribute(r.header, "<PointData", "Vectors") == "force");

  REQUIRE(r.arrays.size() == 2);
  const std::vector<float>* expected[2] = {&scalar, &vec};
  const int components[2] = {1, 3};
  CHECK(r.arrays[0].name == "energy <E>");
  CHECK(r.arrays[1].name == "force");
  for (int a = 0; a < 2; ++a) {
    CAPTURE(a);
    CHECK(r.arrays[a].type == "Float32");
    CHECK(r.arrays[a].format == "appended");
    CHECK(r.arrays[a].components == components[a]);
    CHECK(r.arrays[a].byte_count == 4 * n * components[a]);
    REQUIRE(r.arrays[a].values.size() == expected[a]->size());
    int mismatches = 0;
    for (std::size_t i = 0; i < expected[a]->size(); ++i)
      mismatches += !same_bits(r.arrays[a].values[i], (*expected[a])[i]);
    CHECK(mismatches == 0);
  }
  // Nothing but the closing tags after the last block.
  CHECK(r.tail == "\n  </AppendedData>\n</VTKFile>\n");
}

TEST_CASE("vti export: a one-point grid and a 9-component field") {
  test::TempDir dir;
  GridSpec g;
  g.dims = Eigen::Vector3i(1, 1, 1);
  std::vector<float> m(9);
  for (int i = 0; i < 9; ++i) m[i] = static_cast<float>(i + 1);
  const std::string path = dir.file("one.vti");
  write_vti(path, g, {{"tensor", m.data(), 9}});
  const ReadVti r = read_vti(path);
  CHECK(attribute(r.header, "<ImageData ", "WholeExtent") == "0 0 0 0 0 0");
  REQUIRE(r.arrays.size() == 1);
  CHECK(r.arrays[0].components == 9);
  CHECK(r.arrays[0].values == m);
  CHECK(attribute(r.header, "<PointData", "Scalars").empty());
}

TEST_CASE("vti export: overwriting replaces the file") {
  test::TempDir dir;
  const GridSpec g = small_grid();
  std::vector<float> a(g.count(), 1.0f), b(g.count(), 2.0f);
  const std::string path = dir.file("f.vti");
  write_vti(path, g, {{"a", a.data(), 1}});
  write_vti(path, g, {{"b", b.data(), 1}});
  const ReadVti r = read_vti(path);
  REQUIRE(r.arrays.size() == 1);
  CHECK(r.arrays[0].name == "b");
  CHECK(r.arrays[0].values == b);
  CHECK(files_in(dir.path) == 1);
}

TEST_CASE("vti export: bad input and unwritable paths throw naming the path") {
  test::TempDir dir;
  const GridSpec g = small_grid();
  std::vector<float> v(3 * g.count(), 0.0f);
  const std::string path = dir.file("bad.vti");
  auto message = [&](const GridSpec& grid, const std::vector<GridField>& fields, const std::string& where) {
    try {
      write_vti(where, grid, fields);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };

  GridSpec empty = g;
  empty.dims.z() = 0;
  std::string m = message(empty, {{"a", v.data(), 1}}, path);
  CHECK(m.find(path) != std::string::npos);
  CHECK(m.find("empty grid") != std::string::npos);

  GridSpec flat = g;
  flat.spacing = 0.0;
  CHECK(message(flat, {{"a", v.data(), 1}}, path).find("spacing") != std::string::npos);
  CHECK(message(g, {}, path).find("no fields") != std::string::npos);
  CHECK(message(g, {{"a", nullptr, 1}}, path).find("null") != std::string::npos);
  CHECK(message(g, {{"a", v.data(), 0}}, path).find("1 to 9") != std::string::npos);
  CHECK(message(g, {{"a", v.data(), 10}}, path).find("1 to 9") != std::string::npos);
  CHECK(message(g, {{"", v.data(), 1}}, path).find("empty name") != std::string::npos);
  CHECK(message(g, {{"a", v.data(), 1}, {"a", v.data(), 3}}, path).find("two fields") != std::string::npos);
  CHECK(files_in(dir.path) == 0);

  const std::string nowhere = dir.file("missing-folder/f.vti");
  m = message(g, {{"a", v.data(), 1}}, nowhere);
  CHECK(m.find(nowhere) != std::string::npos);
  CHECK(m.find("cannot create") != std::string::npos);
  CHECK(files_in(dir.path) == 0);
}
