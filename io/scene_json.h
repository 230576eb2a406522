#pragma once
// A scene file's JSON values read with errors that name the file and the field's path,
// e.g. "scenes/x.json: haptics.mass_kg: must be > 0 (got 0)": the primitives of the
// scene reader (io/scene_file.cpp) and of its field tables (io/scene_fields.h).
#include <Eigen/Core>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace snapfit::scene_json {

using json = nlohmann::json;

struct Ctx {
  std::string origin;              // file name, first word of every message
  std::filesystem::path base_dir;  // relative mesh paths are resolved against it
};

// A number as messages and the field docs print it (12 significant digits).
std::string fmt(double v);
std::string join(const std::string& path, const std::string& key);  // "a.b"
std::string at_index(const std::string& path, std::size_t i);       // "a[3]"

[[noreturn]] void fail(const Ctx& c, const std::string& path, const std::string& problem);

void expect_object(const Ctx& c, const json& v, const std::string& path);
// Rejects any key not in `allowed`, naming the full path and the keys that are allowed.
void check_fields(const Ctx& c, const json& obj, const std::string& path, const std::vector<std::string>& allowed);

const json* find(const json& obj, const char* key);
const json& require(const Ctx& c, const json& obj, const std::string& path, const char* key);

double number(const Ctx& c, const json& v, const std::string& path);  // any finite number
std::string text(const Ctx& c, const json& v, const std::string& path);
bool flag(const Ctx& c, const json& v, const std::string& path);  // true or false
double positive(const Ctx& c, const json& v, const std::string& path);
double non_negative(const Ctx& c, const json& v, const std::string& path);
std::vector<double> numbers(const Ctx& c, const json& v, const std::string& path, std::size_t n);
Eigen::Vector3d vec3(const Ctx& c, const json& v, const std::string& path);

}  // namespace snapfit::scene_json
