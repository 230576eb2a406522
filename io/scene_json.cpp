#include "io/scene_json.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include "snapfit/error.h"

namespace snapfit::scene_json {

std::string fmt(double v) {
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}
std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string at_index(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

void fail(const Ctx& c, const std::string& path, const std::string& problem) {
  throw Error(c.origin + ": " + (path.empty() ? "" : path + ": ") + problem);
}

void expect_object(const Ctx& c, const json& v, const std::string& path) {
  if (!v.is_object()) fail(c, path, std::string("expected an object, got ") + v.type_name());
}

void check_fields(const Ctx& c, const json& obj, const std::string& path, const std::vector<std::string>& allowed) {
  expect_object(c, obj, path);
  for (const auto& item : obj.items()) {
    if (std::find(allowed.begin(), allowed.end(), item.key()) != allowed.end()) continue;
    std::string list;
    for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
    fail(c, join(path, item.key()), "unknown field (allowed here: " + list + ")");
  }
}

const json* find(const json& obj, const char* key) {
  const auto it = obj.find(key);
  return it == obj.end() ? nullptr : &*it;
}
const json& require(const Ctx& c, const json& obj, const std::string& path, const char* key) {
  if (const json* v = find(obj, key)) return *v;
  fail(c, join(path, key), "missing (required)");
}

double number(const Ctx& c, const json& v, const std::string& path) {
  if (!v.is_number()) fail(c, path, std::string("expected a number, got ") + v.type_name());
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(c, path, "must be finite");
  return x;
}
std::string text(const Ctx& c, const json& v, const std::string& path) {
  if (!v.is_string()) fail(c, path, std::string("expected a string, got ") + v.type_name());
  return v.get<std::string>();
}
bool flag(const Ctx& c, const json& v, const std::string& path) {
  if (!v.is_boolean()) fail(c, path, "must be true or false");
  return v.get<bool>();
}

double positive(const Ctx& c, const json& v, const std::string& path) {
  const double x = number(c, v, path);
  if (!(x > 0)) fail(c, path, "must be > 0 (got " + fmt(x) + ")");
  return x;
}
double non_negative(const Ctx& c, const json& v, const std::string& path) {
  const double x = number(c, v, path);
  if (!(x >= 0)) fail(c, path, "must be >= 0 (got " + fmt(x) + ")");
  return x;
}

std::vector<double> numbers(const Ctx& c, const json& v, const std::string& path, std::size_t n) {
  if (!v.is_array()) fail(c, path, "expected an array of " + std::to_string(n) + " numbers, got " + v.type_name());
  if (v.size() != n) fail(c, path, "expected " + std::to_string(n) + " numbers, got " + std::to_string(v.size()));
  std::vector<double> out;
  for (std::size_t i = 0; i < n; ++i) out.push_back(number(c, v[i], at_index(path, i)));
  return out;
}
Eigen::Vector3d vec3(const Ctx& c, const json& v, const std::string& path) {
  const auto x = numbers(c, v, path, 3);
  return {x[0], x[1], x[2]};
}

}  // namespace snapfit::scene_json
