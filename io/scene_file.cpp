// Scene files: JSON text <-> Scene, with validation that names the file and the field.
// The format is documented field by field in docs/scenes.md; keep the two in step.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iomanip>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "io/cad_format.h"
#include "mesh/procedural/procedural_parts.h"
#include "snapfit/error.h"
#include "snapfit/scene.h"

namespace snapfit {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

constexpr double kPi = 3.14159265358979323846;
constexpr int kFormatVersion = 1;
constexpr int kMinResolution = 8;
constexpr int kMaxResolution = 1024;
constexpr double kQuaternionNormTolerance = 1e-6;  // |norm - 1| allowed before normalising
constexpr double kSameRotationRad = 1e-9;          // translation scenes: fixed orientation

// ---------------------------------------------------------------- JSON text -> DOM

// Builds the DOM through SAX events so that every syntax error keeps its byte position
// (number overflow included) and duplicate keys are caught with their field path.
class DomBuilder : public nlohmann::json_sax<json> {
 public:
  json root;
  bool has_syntax_error = false;
  std::size_t error_byte = 0;  // characters read when the error was found
  std::string error_text;      // nlohmann's description, without its prefix
  std::string duplicate_path;  // set when a key repeats within one object

  bool null() override { return add(json(nullptr)) != nullptr; }
  bool boolean(bool v) override { return add(json(v)) != nullptr; }
  bool number_integer(number_integer_t v) override { return add(json(v)) != nullptr; }
  bool number_unsigned(number_unsigned_t v) override { return add(json(v)) != nullptr; }
  bool number_float(number_float_t v, const string_t&) override { return add(json(v)) != nullptr; }
  bool string(string_t& v) override { return add(json(v)) != nullptr; }
  bool binary(binary_t& v) override { return add(json::binary(v)) != nullptr; }

  bool start_object(std::size_t) override { return open(json::object(), false); }
  bool start_array(std::size_t) override { return open(json::array(), true); }
  bool end_object() override { return frames_.pop_back(), true; }
  bool end_array() override { return frames_.pop_back(), true; }

  bool key(string_t& k) override {
    Frame& f = frames_.back();
    if (!f.keys.insert(k).second) {
      duplicate_path = f.path.empty() ? k : f.path + "." + k;
      return false;
    }
    f.key = k;
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const json::exception& ex) override {
    has_syntax_error = true;
    error_byte = position;
    std::string what = ex.what();  // "[json.exception.parse_error.101] parse error at ...: text"
    if (const auto close = what.find("] "); close != std::string::npos) what.erase(0, close + 2);
    if (what.rfind("parse error", 0) == 0)
      if (const auto colon = what.find(": "); colon != std::string::npos) what.erase(0, colon + 2);
    error_text = what;
    return false;
  }

 private:
  struct Frame {
    json* node;
    bool is_array;
    std::set<std::string> keys;
    std::string key;
    std::size_t count = 0;
    std::string path;
  };
  std::vector<Frame> frames_;  // open containers, outermost first

  std::string child_path() const {
    if (frames_.empty()) return "";
    const Frame& f = frames_.back();
    if (f.is_array) return f.path + "[" + std::to_string(f.count) + "]";
    return f.path.empty() ? f.key : f.path + "." + f.key;
  }
  json* add(json value) {
    if (frames_.empty()) return &(root = std::move(value));
    Frame& f = frames_.back();
    if (f.is_array) {
      f.node->push_back(std::move(value));
      ++f.count;
      return &f.node->back();
    }
    return &((*f.node)[f.key] = std::move(value));
  }
  bool open(json container, bool is_array) {
    std::string path = child_path();
    json* node = add(std::move(container));
    frames_.push_back(Frame{node, is_array, {}, "", 0, std::move(path)});
    return true;
  }
};

// 1-based line and column of the character at which the parser stopped: the last of
// the `byte` characters it read (the end of the text counts as one character).
std::pair<std::size_t, std::size_t> line_and_column(const std::string& text, std::size_t byte) {
  const std::size_t last = byte == 0 ? 0 : byte - 1;
  std::size_t line = 1, line_start = 0;
  for (std::size_t i = 0; i < std::min(last, text.size()); ++i)
    if (text[i] == '\n') ++line, line_start = i + 1;
  return {line, last - line_start + 1};
}

// ---------------------------------------------------------------- reading helpers

struct Ctx {
  std::string origin;  // file name, first word of every message
  fs::path base_dir;   // relative mesh paths are resolved against it
};

std::string fmt(double v) {
  std::ostringstream os;
  os << std::setprecision(12) << v;
  return os.str();
}
std::string join(const std::string& path, const std::string& key) { return path.empty() ? key : path + "." + key; }
std::string at_index(const std::string& path, std::size_t i) { return path + "[" + std::to_string(i) + "]"; }

[[noreturn]] void fail(const Ctx& c, const std::string& path, const std::string& problem) {
  throw Error(c.origin + ": " + (path.empty() ? "" : path + ": ") + problem);
}

void expect_object(const Ctx& c, const json& v, const std::string& path) {
  if (!v.is_object()) fail(c, path, std::string("expected an object, got ") + v.type_name());
}

// Rejects any key not in `allowed`, naming the full path and the keys that are allowed.
void check_fields(const Ctx& c, const json& obj, const std::string& path, std::initializer_list<const char*> allowed) {
  expect_object(c, obj, path);
  for (const auto& item : obj.items()) {
    if (std::none_of(allowed.begin(), allowed.end(), [&](const char* a) { return item.key() == a; })) {
      std::string list;
      for (const char* a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      fail(c, join(path, item.key()), "unknown field (allowed here: " + list + ")");
    }
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

// ---------------------------------------------------------------- scene pieces

Eigen::Quaterniond read_rotation(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path, {"axis", "angle_deg", "quaternion"});
  const json* axis = find(v, "axis");
  const json* angle = find(v, "angle_deg");
  if (const json* q = find(v, "quaternion")) {
    if (axis || angle) fail(c, path, "give either quaternion or axis + angle_deg, not both");
    const auto w = numbers(c, *q, join(path, "quaternion"), 4);  // [w, x, y, z]
    Eigen::Quaterniond r(w[0], w[1], w[2], w[3]);
    const double norm = r.coeffs().stableNorm();
    if (!(std::abs(norm - 1.0) <= kQuaternionNormTolerance))
      fail(c, join(path, "quaternion"),
           "must be a unit quaternion [w, x, y, z] (norm " + fmt(norm) + ", allowed 1 +- 1e-6)");
    // Renormalise only when it changes something, so written quaternions read back bit-exact.
    if (std::abs(norm - 1.0) > 4 * std::numeric_limits<double>::epsilon()) r.coeffs() /= norm;
    return r;
  }
  if (!axis && !angle) fail(c, path, "needs quaternion, or axis and angle_deg");
  if (!axis) fail(c, join(path, "axis"), "missing (angle_deg needs an axis)");
  if (!angle) fail(c, join(path, "angle_deg"), "missing (axis needs an angle)");
  const Eigen::Vector3d a = vec3(c, *axis, join(path, "axis"));
  const double norm = a.stableNorm();
  if (!(norm > 0) || !std::isfinite(norm)) fail(c, join(path, "axis"), "must be a non-zero vector");
  const double deg = number(c, *angle, join(path, "angle_deg"));
  return Eigen::Quaterniond(Eigen::AngleAxisd(deg * kPi / 180.0, a / norm));
}

// "position" and "rotation" of an object whose fields the caller has checked.
Pose read_pose_fields(const Ctx& c, const json& obj, const std::string& path) {
  Pose pose;
  if (const json* p = find(obj, "position")) pose.translation = vec3(c, *p, join(path, "position"));
  if (const json* r = find(obj, "rotation")) pose.rotation = read_rotation(c, *r, join(path, "rotation"));
  return pose;
}
Pose read_pose(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path, {"position", "rotation"});
  return read_pose_fields(c, v, path);
}

std::string read_unit(const Ctx& c, const json& v, const std::string& path) {
  const std::string unit = text(c, v, path);
  try {
    metres_per_unit(unit);
  } catch (const Error& e) {
    fail(c, path, e.what());
  }
  return unit;
}

ProceduralPartSpec read_procedural(const Ctx& c, const json& v, const std::string& path) {
  expect_object(c, v, path);
  ProceduralPartSpec spec;
  spec.type = text(c, require(c, v, path, "type"), join(path, "type"));
  for (const auto& item : v.items()) {
    if (item.key() == "type") continue;
    const std::string p = join(path, item.key());
    const json& x = item.value();
    if (x.is_number()) {
      spec.numbers[item.key()] = number(c, x, p);
    } else if (x.is_array()) {
      std::vector<double>& arr = spec.arrays[item.key()];
      for (std::size_t i = 0; i < x.size(); ++i) arr.push_back(number(c, x[i], at_index(p, i)));
    } else {
      fail(c, p, std::string("expected a number or an array of numbers, got ") + x.type_name());
    }
  }
  try {
    check_procedural_spec(spec);
  } catch (const Error& e) {  // "<param>: <problem>" -> "FILE: part1.procedural.<param>: <problem>"
    throw Error(c.origin + ": " + path + "." + e.what());
  }
  return spec;
}

CadPartSpec read_cad(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path, {"solid", "deflection", "angular_deflection_deg"});
  CadPartSpec cad;
  if (const json* n = find(v, "solid")) {
    cad.solid = text(c, *n, join(path, "solid"));
    if (cad.solid->empty()) fail(c, join(path, "solid"), "must not be empty");
  }
  if (const json* d = find(v, "deflection")) cad.deflection = positive(c, *d, join(path, "deflection"));
  if (const json* a = find(v, "angular_deflection_deg")) {
    cad.angular_deflection_deg = number(c, *a, join(path, "angular_deflection_deg"));
    if (!(*cad.angular_deflection_deg > 0 && *cad.angular_deflection_deg <= 90))
      fail(c, join(path, "angular_deflection_deg"),
           "must be in (0, 90] (got " + fmt(*cad.angular_deflection_deg) + ")");
  }
  return cad;
}

PartDescriptorSpec read_part_descriptor(const Ctx& c, const json& v, const std::string& path) {
  expect_object(c, v, path);
  check_fields(c, v, path, {"source", "tolerance", "protrusion", "method", "nufft_tolerance"});
  PartDescriptorSpec d;
  if (const json* s = find(v, "source")) {
    const std::string source = text(c, *s, join(path, "source"));
    if (source == "spheres")
      d.source = SpectrumSource::spheres;
    else if (source != "grid")
      fail(c, join(path, "source"), "unknown source '" + source + "' (expected grid or spheres)");
  }
  if (d.source == SpectrumSource::grid) {
    for (const char* key : {"tolerance", "protrusion", "method", "nufft_tolerance"})
      if (find(v, key)) fail(c, join(path, key), "only for source \"spheres\"");
    return d;
  }
  if (const json* x = find(v, "tolerance")) d.tolerance = positive(c, *x, join(path, "tolerance"));
  if (const json* x = find(v, "protrusion")) {
    d.protrusion = number(c, *x, join(path, "protrusion"));
    if (!(d.protrusion >= 0 && d.protrusion <= 1))
      fail(c, join(path, "protrusion"), "must be in [0, 1] (got " + fmt(d.protrusion) + ")");
  }
  if (const json* x = find(v, "method")) {
    d.method = text(c, *x, join(path, "method"));
    if (d.method != "auto" && d.method != "direct" && d.method != "nufft")
      fail(c, join(path, "method"), "unknown method '" + d.method + "' (expected auto, direct or nufft)");
  }
  if (const json* x = find(v, "nufft_tolerance")) {
    d.nufft_tolerance = number(c, *x, join(path, "nufft_tolerance"));
    if (!(d.nufft_tolerance > 0 && d.nufft_tolerance <= 0.1))
      fail(c, join(path, "nufft_tolerance"), "must be in (0, 0.1] (got " + fmt(d.nufft_tolerance) + ")");
  }
  return d;
}

PartSpec read_part(const Ctx& c, const json& v, const std::string& path, const std::string& units) {
  check_fields(c, v, path, {"name", "mesh", "mesh_units", "scale", "cad", "procedural", "pose", "descriptor"});
  PartSpec part;
  part.name = path;  // default: "part1" / "part2"
  if (const json* n = find(v, "name")) part.name = text(c, *n, join(path, "name"));
  const json* mesh = find(v, "mesh");
  const json* proc = find(v, "procedural");
  if (mesh && proc) fail(c, path, "give exactly one of mesh, procedural (got both)");
  if (!mesh && !proc) fail(c, path, "missing mesh or procedural (give exactly one)");
  if (mesh) {
    const std::string rel = text(c, *mesh, join(path, "mesh"));
    if (rel.empty()) fail(c, join(path, "mesh"), "must not be empty");
    const fs::path abs = fs::absolute(c.base_dir / fs::path(rel)).lexically_normal();
    std::error_code ec;
    if (!fs::exists(abs, ec)) fail(c, join(path, "mesh"), "file not found: " + abs.string());
    if (!fs::is_regular_file(abs, ec)) fail(c, join(path, "mesh"), "not a regular file: " + abs.string());
    part.mesh_path = abs.string();
    const bool cad = is_cad_file(rel);
    std::string mesh_units = units;
    if (const json* u = find(v, "mesh_units")) {
      if (cad)
        fail(c, join(path, "mesh_units"),
             "STEP and IGES files declare their own length unit, which is converted to the scene's (use \"scale\" "
             "to scale the part)");
      mesh_units = read_unit(c, *u, join(path, "mesh_units"));
    }
    double scale = 1.0;
    if (const json* s = find(v, "scale")) scale = positive(c, *s, join(path, "scale"));
    part.mesh_scale = cad ? scale : metres_per_unit(mesh_units) / metres_per_unit(units) * scale;
    if (const json* x = find(v, "cad")) {
      if (!cad) fail(c, join(path, "cad"), "only for STEP and IGES files (.step, .stp, .iges, .igs)");
      part.cad = read_cad(c, *x, join(path, "cad"));
    }
  } else {
    for (const char* key : {"mesh_units", "scale", "cad"})
      if (find(v, key)) fail(c, join(path, key), "only for mesh parts (procedural parts use the scene units)");
    part.procedural = read_procedural(c, *proc, join(path, "procedural"));
  }
  if (const json* p = find(v, "pose")) part.pose = read_pose(c, *p, join(path, "pose"));
  if (const json* d = find(v, "descriptor")) part.descriptor = read_part_descriptor(c, *d, join(path, "descriptor"));
  return part;
}

DescriptorParams read_descriptor(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path, {"kind", "sigma", "lambda_in", "lambda_out", "tolerance"});
  DescriptorParams d;
  if (const json* k = find(v, "kind")) {
    const std::string kind = text(c, *k, join(path, "kind"));
    if (kind == "skeletal_density")
      d.kind = DescriptorKind::skeletal_density;
    else if (kind == "indicator")
      d.kind = DescriptorKind::indicator;
    else
      fail(c, join(path, "kind"), "unknown kind '" + kind + "' (expected skeletal_density or indicator)");
  }
  if (d.kind == DescriptorKind::indicator)
    for (const char* key : {"sigma", "lambda_in", "lambda_out"})
      if (find(v, key)) fail(c, join(path, key), "only for kind \"skeletal_density\"");
  if (const json* x = find(v, "sigma")) d.sigma = positive(c, *x, join(path, "sigma"));
  if (const json* x = find(v, "lambda_in")) d.lambda_in = positive(c, *x, join(path, "lambda_in"));
  if (const json* x = find(v, "lambda_out")) d.lambda_out = positive(c, *x, join(path, "lambda_out"));
  if (const json* x = find(v, "tolerance")) {
    d.tolerance = number(c, *x, join(path, "tolerance"));
    if (!(d.tolerance > 0 && d.tolerance < 1))
      fail(c, join(path, "tolerance"), "must be in (0, 1) (got " + fmt(d.tolerance) + ")");
  }
  return d;
}

// "reach", "whole", or a workspace box {"min": [x, y, z], "max": [x, y, z]}.
RegionParams read_region(const Ctx& c, const json& v, const std::string& path) {
  RegionParams r;
  if (v.is_string()) {
    const std::string kind = v.get<std::string>();
    if (kind == "reach")
      r.kind = RegionKind::reach;
    else if (kind == "whole")
      r.kind = RegionKind::whole;
    else
      fail(c, path, "expected \"reach\", \"whole\" or a box {\"min\": [x, y, z], \"max\": [x, y, z]} (got \"" +
                        kind + "\")");
    return r;
  }
  if (!v.is_object())
    fail(c, path, std::string("expected \"reach\", \"whole\" or a box object, got ") + v.type_name());
  check_fields(c, v, path, {"min", "max"});
  r.kind = RegionKind::workspace;
  r.workspace_min = vec3(c, require(c, v, path, "min"), join(path, "min"));
  r.workspace_max = vec3(c, require(c, v, path, "max"), join(path, "max"));
  for (int a = 0; a < 3; ++a)
    if (!(r.workspace_min[a] <= r.workspace_max[a]))
      fail(c, path, "min must not exceed max on any axis (axis " + std::string(1, char('x' + a)) + ": " +
                        fmt(r.workspace_min[a]) + " > " + fmt(r.workspace_max[a]) + ")");
  return r;
}

GridParams read_grid(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path, {"spacing", "resolution", "padding", "region", "region_margin"});
  GridParams g;
  const json* spacing = find(v, "spacing");
  const json* resolution = find(v, "resolution");
  if (spacing && resolution) fail(c, path, "give exactly one of spacing, resolution (got both)");
  if (!spacing && !resolution) fail(c, path, "missing spacing or resolution (give exactly one)");
  if (spacing) g.spacing = positive(c, *spacing, join(path, "spacing"));
  if (resolution) {
    const std::string p = join(path, "resolution");
    const double r = number(c, *resolution, p);
    if (r != std::floor(r)) fail(c, p, "must be an integer (got " + fmt(r) + ")");
    if (r < kMinResolution || r > kMaxResolution)
      fail(c, p,
           "must be in [" + std::to_string(kMinResolution) + ", " + std::to_string(kMaxResolution) + "] (got " +
               fmt(r) + ")");
    g.resolution = static_cast<int>(r);
  }
  if (const json* x = find(v, "padding")) g.padding = non_negative(c, *x, join(path, "padding"));
  if (const json* x = find(v, "region")) g.region = read_region(c, *x, join(path, "region"));
  if (const json* x = find(v, "region_margin"))
    g.region.margin = non_negative(c, *x, join(path, "region_margin"));
  return g;
}

void read_frame(const Ctx& c, const json& v, const std::string& path, Scene& s) {
  check_fields(c, v, path, {"budget_ms", "rate_hz"});
  if (const json* x = find(v, "budget_ms")) s.frame_budget_ms = positive(c, *x, join(path, "budget_ms"));
  if (const json* x = find(v, "rate_hz")) s.loop_rate_hz = positive(c, *x, join(path, "rate_hz"));
  const double period_ms = 1000.0 / s.loop_rate_hz;
  if (s.frame_budget_ms > period_ms)
    fail(c, join(path, "budget_ms"),
         "must not exceed the loop period 1000 / rate_hz = " + fmt(period_ms) + " ms (got " + fmt(s.frame_budget_ms) +
             ")");
}

HapticsParams read_haptics(const Ctx& c, const json& v, const std::string& path) {
  check_fields(
      c, v, path,
      {"mass_kg", "stiffness_n_per_m", "rot_stiffness_nm_per_rad", "damping_ratio", "max_force_n", "max_torque_nm",
       "geometry_gain", "geometry_strength", "settle_s", "success_position", "success_angle_deg", "contact",
       "contact_stiffness_n_per_mm3", "contact_spacing", "max_force_rate_n_per_s", "vouch"});
  HapticsParams h;
  if (const json* x = find(v, "mass_kg")) h.mass_kg = positive(c, *x, join(path, "mass_kg"));
  if (const json* x = find(v, "stiffness_n_per_m"))
    h.stiffness_n_per_m = positive(c, *x, join(path, "stiffness_n_per_m"));
  if (const json* x = find(v, "rot_stiffness_nm_per_rad"))
    h.rot_stiffness_nm_per_rad = positive(c, *x, join(path, "rot_stiffness_nm_per_rad"));
  if (const json* x = find(v, "damping_ratio")) h.damping_ratio = non_negative(c, *x, join(path, "damping_ratio"));
  if (const json* x = find(v, "max_force_n")) h.max_force_n = positive(c, *x, join(path, "max_force_n"));
  if (const json* x = find(v, "max_torque_nm")) h.max_torque_nm = non_negative(c, *x, join(path, "max_torque_nm"));
  if (const json* x = find(v, "geometry_gain")) h.geometry_gain = non_negative(c, *x, join(path, "geometry_gain"));
  if (const json* x = find(v, "geometry_strength"))
    h.geometry_strength = non_negative(c, *x, join(path, "geometry_strength"));
  if (const json* x = find(v, "settle_s")) h.settle_s = non_negative(c, *x, join(path, "settle_s"));
  if (const json* x = find(v, "success_position")) h.success_position = positive(c, *x, join(path, "success_position"));
  if (const json* x = find(v, "success_angle_deg"))
    h.success_angle_deg = positive(c, *x, join(path, "success_angle_deg"));
  if (const json* x = find(v, "contact")) {
    if (!x->is_boolean()) fail(c, join(path, "contact"), "must be true or false");
    h.contact = x->get<bool>();
  }
  if (const json* x = find(v, "contact_stiffness_n_per_mm3"))
    h.contact_stiffness_n_per_mm3 = positive(c, *x, join(path, "contact_stiffness_n_per_mm3"));
  if (const json* x = find(v, "contact_spacing")) h.contact_spacing = positive(c, *x, join(path, "contact_spacing"));
  if (const json* x = find(v, "max_force_rate_n_per_s"))
    h.max_force_rate_n_per_s = non_negative(c, *x, join(path, "max_force_rate_n_per_s"));
  if (const json* x = find(v, "vouch")) {
    if (!x->is_boolean()) fail(c, join(path, "vouch"), "must be true or false");
    h.vouch = x->get<bool>();
  }
  return h;
}

// vps.hybrid: each number in its range, the thresholds ordered, the region by name.
VpsHybridParams read_vps_hybrid(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path,
               {"alignment_fraction", "rotation_fraction", "x_engage", "x_release", "x_full", "ramp_s",
                "radius_tolerance", "offset_tolerance", "angle_tolerance_deg", "region"});
  VpsHybridParams h;
  const auto fraction = [&](const char* field, double& out) {
    if (const json* x = find(v, field)) {
      out = number(c, *x, join(path, field));
      if (!(out > 0 && out < 1))
        fail(c, join(path, field),
             "must be in (0, 1): the user stays stronger than the constraint (got " + fmt(out) + ")");
    }
  };
  fraction("alignment_fraction", h.alignment_fraction);
  fraction("rotation_fraction", h.rotation_fraction);
  const auto unit_interval = [&](const char* field, double& out) {
    if (const json* x = find(v, field)) {
      out = number(c, *x, join(path, field));
      if (!(out > 0 && out <= 1)) fail(c, join(path, field), "must be in (0, 1] (got " + fmt(out) + ")");
    }
  };
  unit_interval("x_engage", h.x_engage);
  unit_interval("x_release", h.x_release);
  unit_interval("x_full", h.x_full);
  if (!(h.x_release < h.x_engage))
    fail(c, join(path, "x_release"),
         "must be below x_engage (got " + fmt(h.x_release) + " against " + fmt(h.x_engage) + ")");
  if (const json* x = find(v, "ramp_s")) h.ramp_s = non_negative(c, *x, join(path, "ramp_s"));
  if (const json* x = find(v, "radius_tolerance")) h.radius_tolerance = positive(c, *x, join(path, "radius_tolerance"));
  if (const json* x = find(v, "offset_tolerance")) h.offset_tolerance = positive(c, *x, join(path, "offset_tolerance"));
  if (const json* x = find(v, "angle_tolerance_deg")) {
    h.angle_tolerance_deg = positive(c, *x, join(path, "angle_tolerance_deg"));
    if (*h.angle_tolerance_deg > 90)
      fail(c, join(path, "angle_tolerance_deg"), "must be in (0, 90] (got " + fmt(*h.angle_tolerance_deg) + ")");
  }
  if (const json* x = find(v, "region")) {
    const std::string r = text(c, *x, join(path, "region"));
    if (r == "pair")
      h.region = HybridRegion::pair;
    else if (r == "face")
      h.region = HybridRegion::face;
    else
      fail(c, join(path, "region"), "unknown region '" + r + "' (expected pair or face)");
  }
  return h;
}

VpsParams read_vps(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path,
               {"voxel_size", "stiffness_n_per_m", "shell_density", "proximity_layers", "braking_n_s_per_m", "hybrid"});
  VpsParams p;
  if (const json* x = find(v, "hybrid")) p.hybrid = read_vps_hybrid(c, *x, join(path, "hybrid"));
  if (const json* x = find(v, "voxel_size")) p.voxel_size = positive(c, *x, join(path, "voxel_size"));
  if (const json* x = find(v, "stiffness_n_per_m"))
    p.stiffness_n_per_m = positive(c, *x, join(path, "stiffness_n_per_m"));
  if (const json* x = find(v, "shell_density")) {
    p.shell_density = positive(c, *x, join(path, "shell_density"));
    if (p.shell_density > 8) fail(c, join(path, "shell_density"), "must be <= 8 (got " + fmt(p.shell_density) + ")");
  }
  if (const json* x = find(v, "proximity_layers")) {
    const double layers = non_negative(c, *x, join(path, "proximity_layers"));
    if (layers != std::floor(layers) || layers > 16)
      fail(c, join(path, "proximity_layers"), "must be an integer in [0, 16] (got " + fmt(layers) + ")");
    p.proximity_layers = static_cast<int>(layers);
  }
  if (const json* x = find(v, "braking_n_s_per_m"))
    p.braking_n_s_per_m = non_negative(c, *x, join(path, "braking_n_s_per_m"));
  return p;
}

Method read_method(const Ctx& c, const json& v, const std::string& path) {
  const std::string m = text(c, v, path);
  if (const std::optional<Method> method = method_named(m)) return *method;
  fail(c, path, "unknown method '" + m + "' (expected " + method_names() + ")");
}

Motion read_motion(const Ctx& c, const json& v, const std::string& path) {
  const std::string m = text(c, v, path);
  if (const std::optional<Motion> motion = motion_named(m)) return *motion;
  fail(c, path, "unknown motion '" + m + "' (expected " + motion_names() + ")");
}

Outputs read_outputs(const Ctx& c, const json& v, const std::string& path, Motion motion) {
  if (!v.is_array()) fail(c, path, std::string("expected an array of strings, got ") + v.type_name());
  if (v.empty()) fail(c, path, "must list at least one of energy, force, torque");
  Outputs o{false, false, false};
  for (std::size_t i = 0; i < v.size(); ++i) {
    const std::string p = at_index(path, i);
    const std::string name = text(c, v[i], p);
    bool* flag = name == "energy" ? &o.energy : name == "force" ? &o.force : name == "torque" ? &o.torque : nullptr;
    if (!flag) fail(c, p, "unknown output '" + name + "' (expected energy, force or torque)");
    if (*flag) fail(c, p, "'" + name + "' listed twice");
    *flag = true;
  }
  if (o.torque && motion == Motion::translation)
    fail(c, path, "torque needs motion \"6dof\" (this scene's motion is \"translation\")");
  o.energy = true;  // force and torque are derivatives of the energy: it is always available
  return o;
}

Trajectory read_trajectory(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path, {"keyframes"});
  const std::string kpath = join(path, "keyframes");
  const json& keys = require(c, v, path, "keyframes");
  if (!keys.is_array()) fail(c, kpath, std::string("expected an array of keyframes, got ") + keys.type_name());
  if (keys.empty()) fail(c, kpath, "must hold at least one keyframe (or leave out trajectory)");
  Trajectory t;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string p = at_index(kpath, i);
    check_fields(c, keys[i], p, {"time_s", "position", "rotation"});
    Keyframe k;
    k.time_s = number(c, require(c, keys[i], p, "time_s"), join(p, "time_s"));
    if (i == 0 && !(k.time_s >= 0)) fail(c, join(p, "time_s"), "must be >= 0 (got " + fmt(k.time_s) + ")");
    if (i > 0 && !(k.time_s > t.keyframes.back().time_s))
      fail(c, join(p, "time_s"),
           "must be greater than the previous keyframe's time " + fmt(t.keyframes.back().time_s) + " (got " +
               fmt(k.time_s) + ")");
    k.pose = read_pose_fields(c, keys[i], p);
    t.keyframes.push_back(k);
  }
  return t;
}

// In a translation-only scene part 2 keeps part2.pose's orientation throughout.
void check_fixed_orientation(const Ctx& c, const Scene& s, const Pose& pose, const std::string& path) {
  if (pose.rotation.angularDistance(s.part2.pose.rotation) > kSameRotationRad)
    fail(c, path, "motion is \"translation\": the rotation must equal part2.pose.rotation");
}

Scene read_scene(const Ctx& c, const json& root) {
  if (!root.is_object()) throw Error(c.origin + ": expected a JSON object at the top level, got " + root.type_name());
  // The version first: a file that is not a scene at all should say so.
  const json* version = find(root, "snapfit_scene");
  if (!version) fail(c, "snapfit_scene", "missing (the format version, must be 1)");
  if (!version->is_number()) fail(c, "snapfit_scene", std::string("expected a number, got ") + version->type_name());
  if (version->get<double>() != kFormatVersion)
    fail(c, "snapfit_scene", "unsupported format version " + fmt(version->get<double>()) + " (this build reads 1)");
  check_fields(c, root, "",
               {"snapfit_scene", "name", "units", "part1", "part2", "assembled_pose", "descriptor", "grid", "frame",
                "outputs", "motion", "trajectory", "haptics", "method", "vps"});

  Scene s;
  s.source_path = c.origin;
  if (const json* n = find(root, "name")) s.name = text(c, *n, "name");
  s.units = read_unit(c, require(c, root, "", "units"), "units");
  s.part1 = read_part(c, require(c, root, "", "part1"), "part1", s.units);
  s.part2 = read_part(c, require(c, root, "", "part2"), "part2", s.units);
  if (const json* a = find(root, "assembled_pose")) s.assembled_pose = read_pose(c, *a, "assembled_pose");
  if (const json* d = find(root, "descriptor")) s.descriptor = read_descriptor(c, *d, "descriptor");
  s.grid = read_grid(c, require(c, root, "", "grid"), "grid");
  if (const json* f = find(root, "frame")) read_frame(c, *f, "frame", s);
  if (const json* m = find(root, "motion")) s.motion = read_motion(c, *m, "motion");
  if (const json* o = find(root, "outputs"))
    s.outputs = read_outputs(c, *o, "outputs", s.motion);
  else
    s.outputs = Outputs{true, true, s.motion == Motion::six_dof};
  if (const json* t = find(root, "trajectory")) s.trajectory = read_trajectory(c, *t, "trajectory");
  if (const json* h = find(root, "haptics")) s.haptics = read_haptics(c, *h, "haptics");
  if (const json* m = find(root, "method")) s.method = read_method(c, *m, "method");
  if (const json* v = find(root, "vps")) s.vps = read_vps(c, *v, "vps");

  for (const auto& [part, name] : {std::pair{&s.part1, "part1"}, std::pair{&s.part2, "part2"}})
    if (part->descriptor.source == SpectrumSource::spheres && s.descriptor.kind != DescriptorKind::indicator)
      fail(c, join(name, "descriptor.source"),
           "\"spheres\" gives the indicator descriptor only (seed 001 defines ball sums, not the skeletal density); "
           "set descriptor.kind to \"indicator\"");
  if (s.motion == Motion::translation) {
    if (s.assembled_pose) check_fixed_orientation(c, s, *s.assembled_pose, "assembled_pose.rotation");
    for (std::size_t i = 0; i < s.trajectory.keyframes.size(); ++i)
      check_fixed_orientation(c, s, s.trajectory.keyframes[i].pose, at_index("trajectory.keyframes", i) + ".rotation");
  }
  return s;
}

// ---------------------------------------------------------------- writing

ordered_json pose_json(const Pose& p) {
  const Eigen::Quaterniond& q = p.rotation;
  ordered_json j;
  j["position"] = {p.translation.x(), p.translation.y(), p.translation.z()};
  j["rotation"] = {{"quaternion", {q.w(), q.x(), q.y(), q.z()}}};
  return j;
}

ordered_json part_json(const PartSpec& part, const std::string& units, const std::string& source_path) {
  ordered_json j;
  j["name"] = part.name;
  if (part.mesh_path) {
    fs::path p(*part.mesh_path);
    if (p.is_relative()) {  // relative to the scene file's folder, or to the working directory
      const fs::path base = source_path.empty() ? fs::path() : fs::path(source_path).parent_path();
      p = fs::absolute(base / p).lexically_normal();
    }
    j["mesh"] = p.string();
    if (is_cad_file(p.string())) {
      j["scale"] = part.mesh_scale;  // the reader converts the file's own unit
      ordered_json cad = ordered_json::object();
      if (part.cad.solid) cad["solid"] = *part.cad.solid;
      if (part.cad.deflection) cad["deflection"] = *part.cad.deflection;
      if (part.cad.angular_deflection_deg) cad["angular_deflection_deg"] = *part.cad.angular_deflection_deg;
      if (!cad.empty()) j["cad"] = cad;
    } else {
      j["mesh_units"] = units;  // mesh_scale already converts file units to scene units
      j["scale"] = part.mesh_scale;
    }
  }
  if (part.procedural) {
    ordered_json proc;
    proc["type"] = part.procedural->type;
    for (const auto& [k, v] : part.procedural->numbers) proc[k] = v;
    for (const auto& [k, v] : part.procedural->arrays) proc[k] = v;
    j["procedural"] = proc;
  }
  j["pose"] = pose_json(part.pose);
  if (part.descriptor.source == SpectrumSource::spheres) {
    ordered_json d;
    d["source"] = "spheres";
    if (part.descriptor.tolerance) d["tolerance"] = *part.descriptor.tolerance;
    d["protrusion"] = part.descriptor.protrusion;
    d["method"] = part.descriptor.method;
    d["nufft_tolerance"] = part.descriptor.nufft_tolerance;
    j["descriptor"] = d;
  }
  return j;
}

// One JSON value as text: objects one field per line, arrays of plain values on one
// line; integral numbers without ".0". Doubles print with round-trip precision.
void write_value(std::string& out, const ordered_json& v, int indent, const std::string& path) {
  const std::string pad(indent, ' '), inner(indent + 2, ' ');
  if (v.is_object() && !v.empty()) {
    out += "{\n";
    std::size_t i = 0;
    for (const auto& item : v.items()) {
      out += inner + ordered_json(item.key()).dump() + ": ";
      write_value(out, item.value(), indent + 2, join(path, item.key()));
      out += ++i < v.size() ? ",\n" : "\n";
    }
    out += pad + "}";
  } else if (v.is_array() && !v.empty()) {
    const bool nested = std::any_of(v.begin(), v.end(), [](const ordered_json& e) { return e.is_structured(); });
    out += nested ? "[\n" : "[";
    for (std::size_t i = 0; i < v.size(); ++i) {
      if (nested) out += inner;
      write_value(out, v[i], indent + 2, at_index(path, i));
      if (i + 1 < v.size()) out += nested ? ",\n" : ", ";
    }
    out += nested ? "\n" + pad + "]" : "]";
  } else if (v.is_number_float()) {
    const double x = v.get<double>();
    if (!std::isfinite(x)) throw Error("scene_to_json: " + path + ": not a finite number");
    const bool integral = x == std::floor(x) && std::abs(x) < 1e15 && !(x == 0 && std::signbit(x));
    out += integral ? std::to_string(static_cast<long long>(x)) : v.dump();
  } else {
    out += v.dump();
  }
}

std::string read_file(const std::string& path) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path + ": file not found");
  if (!fs::is_regular_file(path, ec)) throw Error(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path + ": cannot open file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error(path + ": cannot read file");
  return text.str();
}

}  // namespace

Scene parse_scene(const std::string& json_text, const std::string& origin) {
  Ctx c{origin, fs::path(origin).parent_path()};
  if (c.base_dir.empty()) c.base_dir = fs::current_path();
  DomBuilder dom;
  if (!json::sax_parse(json_text, &dom, json::input_format_t::json, true, false)) {
    if (!dom.duplicate_path.empty()) throw Error(origin + ": " + dom.duplicate_path + ": duplicate field");
    const auto [line, column] = line_and_column(json_text, dom.error_byte);
    throw Error(origin + ": invalid JSON at line " + std::to_string(line) + ", column " + std::to_string(column) +
                ": " + dom.error_text);
  }
  return read_scene(c, dom.root);
}

Scene load_scene(const std::string& path) { return parse_scene(read_file(path), path); }

std::string scene_to_json(const Scene& s) {
  ordered_json j;
  j["snapfit_scene"] = kFormatVersion;
  j["name"] = s.name;
  j["units"] = s.units;
  j["part1"] = part_json(s.part1, s.units, s.source_path);
  j["part2"] = part_json(s.part2, s.units, s.source_path);
  if (s.assembled_pose) j["assembled_pose"] = pose_json(*s.assembled_pose);

  ordered_json d;
  const bool skeletal = s.descriptor.kind == DescriptorKind::skeletal_density;
  d["kind"] = skeletal ? "skeletal_density" : "indicator";
  if (skeletal) {
    d["sigma"] = s.descriptor.sigma;
    d["lambda_in"] = s.descriptor.lambda_in;
    d["lambda_out"] = s.descriptor.lambda_out;
  }
  d["tolerance"] = s.descriptor.tolerance;
  j["descriptor"] = d;

  ordered_json g;
  if (s.grid.spacing) g["spacing"] = *s.grid.spacing;
  if (s.grid.resolution) g["resolution"] = *s.grid.resolution;
  g["padding"] = s.grid.padding;
  const RegionParams& r = s.grid.region;
  if (r.kind == RegionKind::whole) g["region"] = "whole";
  if (r.kind == RegionKind::workspace)
    g["region"] = {{"min", {r.workspace_min.x(), r.workspace_min.y(), r.workspace_min.z()}},
                   {"max", {r.workspace_max.x(), r.workspace_max.y(), r.workspace_max.z()}}};
  if (r.margin) g["region_margin"] = *r.margin;
  j["grid"] = g;

  j["frame"] = {{"budget_ms", s.frame_budget_ms}, {"rate_hz", s.loop_rate_hz}};
  ordered_json outputs = ordered_json::array();
  if (s.outputs.energy) outputs.push_back("energy");
  if (s.outputs.force) outputs.push_back("force");
  if (s.outputs.torque) outputs.push_back("torque");
  j["outputs"] = outputs;
  j["motion"] = motion_name(s.motion);

  if (!s.trajectory.keyframes.empty()) {
    ordered_json keys = ordered_json::array();
    for (const Keyframe& k : s.trajectory.keyframes) {
      const ordered_json pose = pose_json(k.pose);
      ordered_json kj;
      kj["time_s"] = k.time_s;
      kj["position"] = pose["position"];
      kj["rotation"] = pose["rotation"];
      keys.push_back(kj);
    }
    j["trajectory"] = {{"keyframes", keys}};
  }
  const HapticsParams& h = s.haptics;
  ordered_json hj;
  hj["mass_kg"] = h.mass_kg;
  hj["stiffness_n_per_m"] = h.stiffness_n_per_m;
  if (h.rot_stiffness_nm_per_rad) hj["rot_stiffness_nm_per_rad"] = *h.rot_stiffness_nm_per_rad;
  hj["damping_ratio"] = h.damping_ratio;
  hj["max_force_n"] = h.max_force_n;
  hj["max_torque_nm"] = h.max_torque_nm;
  if (h.geometry_gain) hj["geometry_gain"] = *h.geometry_gain;
  hj["geometry_strength"] = h.geometry_strength;
  hj["settle_s"] = h.settle_s;
  if (h.success_position) hj["success_position"] = *h.success_position;
  hj["success_angle_deg"] = h.success_angle_deg;
  hj["contact"] = h.contact;
  hj["contact_stiffness_n_per_mm3"] = h.contact_stiffness_n_per_mm3;
  if (h.contact_spacing) hj["contact_spacing"] = *h.contact_spacing;
  hj["max_force_rate_n_per_s"] = h.max_force_rate_n_per_s;
  hj["vouch"] = h.vouch;
  j["haptics"] = hj;
  j["method"] = method_name(s.method);
  ordered_json vj;
  if (s.vps.voxel_size) vj["voxel_size"] = *s.vps.voxel_size;
  vj["stiffness_n_per_m"] = s.vps.stiffness_n_per_m;
  vj["shell_density"] = s.vps.shell_density;
  vj["proximity_layers"] = s.vps.proximity_layers;
  if (s.vps.braking_n_s_per_m) vj["braking_n_s_per_m"] = *s.vps.braking_n_s_per_m;
  const VpsHybridParams& hy = s.vps.hybrid;
  ordered_json hj2;
  hj2["alignment_fraction"] = hy.alignment_fraction;
  hj2["rotation_fraction"] = hy.rotation_fraction;
  hj2["x_engage"] = hy.x_engage;
  hj2["x_release"] = hy.x_release;
  hj2["x_full"] = hy.x_full;
  hj2["ramp_s"] = hy.ramp_s;
  if (hy.radius_tolerance) hj2["radius_tolerance"] = *hy.radius_tolerance;
  if (hy.offset_tolerance) hj2["offset_tolerance"] = *hy.offset_tolerance;
  if (hy.angle_tolerance_deg) hj2["angle_tolerance_deg"] = *hy.angle_tolerance_deg;
  hj2["region"] = hy.region == HybridRegion::face ? "face" : "pair";
  vj["hybrid"] = hj2;
  j["vps"] = vj;
  std::string out;
  write_value(out, j, 0, "");
  return out + "\n";
}

}  // namespace snapfit
