// Scene files: JSON text <-> Scene, with validation that names the file and the field.
// Each section's fields, their defaults and allowed values are described once, in
// io/scene_fields.cpp, which docs/scenes.md's tables are printed from; this file reads
// and writes the fields that need code of their own (parts, poses, the region, outputs,
// keyframes) and the checks across fields.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/cad_format.h"
#include "io/json_dom.h"
#include "io/scene_fields.h"
#include "io/scene_json.h"
#include "mesh/procedural/procedural_parts.h"
#include "snapfit/error.h"
#include "snapfit/pose_json.h"
#include "snapfit/scene.h"

namespace snapfit {
namespace {

namespace fs = std::filesystem;
using namespace scene_json;
using namespace scene_schema;
using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

constexpr double kPi = 3.14159265358979323846;
constexpr int kFormatVersion = 1;
constexpr double kQuaternionNormTolerance = 1e-6;  // |norm - 1| allowed before normalising
constexpr double kSameRotationRad = 1e-9;          // translation scenes: fixed orientation

// ---------------------------------------------------------------- reading

Eigen::Quaterniond read_rotation(const Ctx& c, const json& v, const std::string& path) {
  check_fields(c, v, path, names_of(rotation_fields()));
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
  check_fields(c, v, path, names_of(pose_fields()));
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

PartSpec read_part(const Ctx& c, const json& v, const std::string& path, const std::string& units) {
  PartSpec part;
  part.name = path;  // default: "part1" / "part2"
  read_fields(c, v, path, part_fields(), part);
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
      read_fields(c, *x, join(path, "cad"), cad_fields(), part.cad);
    }
  } else {
    for (const char* key : {"mesh_units", "scale", "cad"})
      if (find(v, key)) fail(c, join(path, key), "only for mesh parts (procedural parts use the scene units)");
    part.procedural = read_procedural(c, *proc, join(path, "procedural"));
  }
  if (const json* p = find(v, "pose")) part.pose = read_pose(c, *p, join(path, "pose"));
  if (const json* d = find(v, "descriptor"))
    read_fields(c, *d, join(path, "descriptor"), part_descriptor_fields(), part.descriptor);
  return part;
}

RegionParams read_region(const Ctx& c, const json& v, const std::string& path) {
  RegionParams r;
  if (v.is_string()) {
    const std::string kind = v.get<std::string>();
    if (kind == "reach")
      r.kind = RegionKind::reach;
    else if (kind == "whole")
      r.kind = RegionKind::whole;
    else
      fail(c, path,
           "expected \"reach\", \"whole\" or a box {\"min\": [x, y, z], \"max\": [x, y, z]} (got \"" + kind + "\")");
    return r;
  }
  if (!v.is_object()) fail(c, path, std::string("expected \"reach\", \"whole\" or a box object, got ") + v.type_name());
  check_fields(c, v, path, {"min", "max"});
  r.kind = RegionKind::workspace;
  r.workspace_min = vec3(c, require(c, v, path, "min"), join(path, "min"));
  r.workspace_max = vec3(c, require(c, v, path, "max"), join(path, "max"));
  for (int a = 0; a < 3; ++a)
    if (!(r.workspace_min[a] <= r.workspace_max[a]))
      fail(c, path,
           "min must not exceed max on any axis (axis " + std::string(1, char('x' + a)) + ": " +
               fmt(r.workspace_min[a]) + " > " + fmt(r.workspace_max[a]) + ")");
  return r;
}

// The grid: exactly one of spacing and resolution; the region by hand.
GridParams read_grid(const Ctx& c, const json& v, const std::string& path) {
  expect_object(c, v, path);
  const json* spacing = find(v, "spacing");
  const json* resolution = find(v, "resolution");
  if (spacing && resolution) fail(c, path, "give exactly one of spacing, resolution (got both)");
  if (!spacing && !resolution) fail(c, path, "missing spacing or resolution (give exactly one)");
  GridParams g;
  read_fields(c, v, path, grid_fields(), g);
  if (const json* x = find(v, "region")) g.region = read_region(c, *x, join(path, "region"));
  if (const json* x = find(v, "region_margin")) g.region.margin = non_negative(c, *x, join(path, "region_margin"));
  return g;
}

// The frame: its budget within the loop's period.
void read_frame(const Ctx& c, const json& v, const std::string& path, Scene& s) {
  read_fields(c, v, path, frame_fields(), s);
  const double period_ms = 1000.0 / s.loop_rate_hz;
  if (s.frame_budget_ms > period_ms)
    fail(c, join(path, "budget_ms"),
         "must not exceed the loop period 1000 / rate_hz = " + fmt(period_ms) + " ms (got " + fmt(s.frame_budget_ms) +
             ")");
}

// vps, with vps.hybrid's thresholds ordered.
VpsParams read_vps(const Ctx& c, const json& v, const std::string& path) {
  VpsParams p;
  read_fields(c, v, path, vps_fields(), p);
  if (const json* x = find(v, "hybrid")) {
    const std::string hybrid = join(path, "hybrid");
    read_fields(c, *x, hybrid, vps_hybrid_fields(), p.hybrid);
    if (!(p.hybrid.x_release < p.hybrid.x_engage))
      fail(c, join(hybrid, "x_release"),
           "must be below x_engage (got " + fmt(p.hybrid.x_release) + " against " + fmt(p.hybrid.x_engage) + ")");
  }
  return p;
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
  check_fields(c, v, path, names_of(trajectory_fields()));
  const std::string kpath = join(path, "keyframes");
  const json& keys = require(c, v, path, "keyframes");
  if (!keys.is_array()) fail(c, kpath, std::string("expected an array of keyframes, got ") + keys.type_name());
  if (keys.empty()) fail(c, kpath, "must hold at least one keyframe (or leave out trajectory)");
  Trajectory t;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string p = at_index(kpath, i);
    check_fields(c, keys[i], p, names_of(keyframe_fields()));
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

  Scene s;
  read_fields(c, root, "", top_fields(), s);  // name, motion, method
  s.source_path = c.origin;
  s.units = read_unit(c, require(c, root, "", "units"), "units");
  s.part1 = read_part(c, require(c, root, "", "part1"), "part1", s.units);
  s.part2 = read_part(c, require(c, root, "", "part2"), "part2", s.units);
  if (const json* a = find(root, "assembled_pose")) s.assembled_pose = read_pose(c, *a, "assembled_pose");
  if (const json* d = find(root, "descriptor")) read_fields(c, *d, "descriptor", descriptor_fields(), s.descriptor);
  s.grid = read_grid(c, require(c, root, "", "grid"), "grid");
  if (const json* f = find(root, "frame")) read_frame(c, *f, "frame", s);
  if (const json* o = find(root, "outputs"))
    s.outputs = read_outputs(c, *o, "outputs", s.motion);
  else
    s.outputs = Outputs{true, true, s.motion == Motion::six_dof};
  if (const json* t = find(root, "trajectory")) s.trajectory = read_trajectory(c, *t, "trajectory");
  if (const json* h = find(root, "haptics")) read_fields(c, *h, "haptics", haptics_fields(), s.haptics);
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

ordered_json part_json(const PartSpec& part, const std::string& units, const std::string& source_path) {
  ordered_json by_hand;
  if (part.mesh_path) {
    fs::path p(*part.mesh_path);
    if (p.is_relative()) {  // relative to the scene file's folder, or to the working directory
      const fs::path base = source_path.empty() ? fs::path() : fs::path(source_path).parent_path();
      p = fs::absolute(base / p).lexically_normal();
    }
    by_hand["mesh"] = p.string();
    if (is_cad_file(p.string())) {
      by_hand["scale"] = part.mesh_scale;  // the reader converts the file's own unit
      const ordered_json cad = write_fields(cad_fields(), part.cad);
      if (!cad.empty()) by_hand["cad"] = cad;
    } else {
      by_hand["mesh_units"] = units;  // mesh_scale already converts file units to scene units
      by_hand["scale"] = part.mesh_scale;
    }
  }
  if (part.procedural) {
    ordered_json proc;
    proc["type"] = part.procedural->type;
    for (const auto& [k, v] : part.procedural->numbers) proc[k] = v;
    for (const auto& [k, v] : part.procedural->arrays) proc[k] = v;
    by_hand["procedural"] = proc;
  }
  by_hand["pose"] = pose_json<ordered_json>(part.pose);
  if (part.descriptor.source == SpectrumSource::spheres)
    by_hand["descriptor"] = write_fields(part_descriptor_fields(), part.descriptor);
  return write_fields(part_fields(), part, by_hand);
}

ordered_json grid_json(const GridParams& g) {
  ordered_json by_hand;
  const RegionParams& r = g.region;
  if (r.kind == RegionKind::whole) by_hand["region"] = "whole";
  if (r.kind == RegionKind::workspace)
    by_hand["region"] = {{"min", {r.workspace_min.x(), r.workspace_min.y(), r.workspace_min.z()}},
                         {"max", {r.workspace_max.x(), r.workspace_max.y(), r.workspace_max.z()}}};
  if (r.margin) by_hand["region_margin"] = *r.margin;
  return write_fields(grid_fields(), g, by_hand);
}

ordered_json trajectory_json(const Trajectory& t) {
  ordered_json keys = ordered_json::array();
  for (const Keyframe& k : t.keyframes) {
    ordered_json by_hand = pose_json<ordered_json>(k.pose);
    by_hand["time_s"] = k.time_s;
    keys.push_back(write_fields(keyframe_fields(), k, by_hand));
  }
  return write_fields(trajectory_fields(), t, {{"keyframes", keys}});
}

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
  return read_scene(c, parse_json_dom(json_text, origin));
}

Scene load_scene(const std::string& path) { return parse_scene(read_file(path), path); }

std::string scene_to_json(const Scene& s) {
  ordered_json by_hand;
  by_hand["snapfit_scene"] = kFormatVersion;
  by_hand["units"] = s.units;
  by_hand["part1"] = part_json(s.part1, s.units, s.source_path);
  by_hand["part2"] = part_json(s.part2, s.units, s.source_path);
  if (s.assembled_pose) by_hand["assembled_pose"] = pose_json<ordered_json>(*s.assembled_pose);
  by_hand["descriptor"] = write_fields(descriptor_fields(), s.descriptor);
  by_hand["grid"] = grid_json(s.grid);
  by_hand["frame"] = write_fields(frame_fields(), s);
  ordered_json outputs = ordered_json::array();
  if (s.outputs.energy) outputs.push_back("energy");
  if (s.outputs.force) outputs.push_back("force");
  if (s.outputs.torque) outputs.push_back("torque");
  by_hand["outputs"] = outputs;
  if (!s.trajectory.keyframes.empty()) by_hand["trajectory"] = trajectory_json(s.trajectory);
  by_hand["haptics"] = write_fields(haptics_fields(), s.haptics);
  ordered_json vps = write_fields(vps_fields(), s.vps, {{"hybrid", write_fields(vps_hybrid_fields(), s.vps.hybrid)}});
  by_hand["vps"] = vps;
  std::string out;
  write_value(out, write_fields(top_fields(), s, by_hand), 0, "");
  return out + "\n";
}

}  // namespace snapfit
