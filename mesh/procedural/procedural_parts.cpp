// Parameter checking and dispatch for the procedural parts (procedural_parts.h).
// Every message is "<field>: <problem> (got <value>)" so callers can prefix the path.
#include "mesh/procedural/procedural_parts.h"

#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <vector>

#include "mesh/procedural/procedural_internal.h"
#include "snapfit/error.h"

namespace snapfit {

namespace {

using procedural::kMaxSegments;
using procedural::kMinWallFraction;

std::string show(double v) {
  std::ostringstream s;
  s.precision(12);
  s << v;
  return s.str();
}

std::string show(const std::vector<double>& v) {
  std::string out = "[";
  for (size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + show(v[i]);
  return out + "]";
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (size_t i = 0; i < names.size(); ++i) out += (i ? ", " : "") + names[i];
  return out;
}

[[noreturn]] void fail(const std::string& field, const std::string& problem, const std::string& got) {
  throw Error(field + ": " + problem + " (got " + got + ")");
}

// Reads one spec against the parameter names its type declares.
struct Params {
  const ProceduralPartSpec& spec;

  // Every name must be declared, as a number or as an array, and given as that kind.
  void check_names(const std::vector<std::string>& numbers, const std::vector<std::string>& arrays) const {
    auto declared = [](const std::vector<std::string>& list, const std::string& name) {
      for (const std::string& s : list)
        if (s == name) return true;
      return false;
    };
    std::vector<std::string> unknown;
    for (const auto& [name, value] : spec.numbers) {
      if (declared(numbers, name)) continue;
      if (declared(arrays, name)) fail(name, "must be an array of 3 numbers", "the number " + show(value));
      unknown.push_back(name);
    }
    for (const auto& [name, value] : spec.arrays) {
      if (declared(arrays, name)) continue;
      if (declared(numbers, name)) fail(name, "must be a number, not an array", show(value));
      unknown.push_back(name);
    }
    if (!unknown.empty()) {
      std::vector<std::string> known = numbers;
      known.insert(known.end(), arrays.begin(), arrays.end());
      std::string problem = "unknown parameter for " + spec.type;
      if (unknown.size() > 1) problem += " (also unknown: " + join({unknown.begin() + 1, unknown.end()}) + ")";
      throw Error(unknown.front() + ": " + problem + "; known parameters: " + join(known));
    }
  }

  std::optional<double> optional_number(const std::string& name) const {
    const auto it = spec.numbers.find(name);
    if (it == spec.numbers.end()) return std::nullopt;
    if (!std::isfinite(it->second)) fail(name, "must be a finite number", show(it->second));
    return it->second;
  }

  double required(const std::string& name) const {
    const std::optional<double> v = optional_number(name);
    if (!v) throw Error(name + ": missing (required for " + spec.type + ")");
    return *v;
  }

  double positive(const std::string& name) const {
    const double v = required(name);
    if (!(v > 0)) fail(name, "must be > 0", show(v));
    return v;
  }

  double non_negative(const std::string& name, double fallback) const {
    const double v = optional_number(name).value_or(fallback);
    if (!(v >= 0)) fail(name, "must be >= 0", show(v));
    return v;
  }

  // Integer multiple of 8, at least 8: the N-gon then has vertices on the axes and the
  // diagonals, which the hole block and the three-peg cells rely on.
  int segments() const {
    const double v = optional_number("segments").value_or(procedural::kDefaultSegments);
    if (v != std::floor(v) || v < 8 || v > kMaxSegments || std::fmod(v, 8.0) != 0)
      fail("segments", "must be a multiple of 8 from 8 to " + std::to_string(kMaxSegments), show(v));
    return static_cast<int>(v);
  }

  // Array of exactly 3 finite numbers, each > 0 (strict) or >= 0; `fallback` fills a
  // missing optional array, none makes it required.
  std::array<double, 3> array3(const std::string& name, bool strict, std::optional<double> fallback) const {
    const auto it = spec.arrays.find(name);
    if (it == spec.arrays.end()) {
      if (!fallback) throw Error(name + ": missing (required for " + spec.type + ")");
      return {*fallback, *fallback, *fallback};
    }
    const std::vector<double>& v = it->second;
    if (v.size() != 3) fail(name, "must have 3 entries", std::to_string(v.size()) + ": " + show(v));
    std::array<double, 3> out{};
    for (int k = 0; k < 3; ++k) {
      const std::string field = name + "[" + std::to_string(k) + "]";
      if (!std::isfinite(v[k])) fail(field, "must be a finite number", show(v[k]));
      if (strict && !(v[k] > 0)) fail(field, "must be > 0", show(v[k]));
      if (!strict && !(v[k] >= 0)) fail(field, "must be >= 0", show(v[k]));
      out[k] = v[k];
    }
    return out;
  }
};

procedural::PegParams read_peg(const Params& in) {
  in.check_names({"radius", "length", "chamfer", "segments"}, {});
  procedural::PegParams p;
  p.segments = in.segments();
  p.radius = in.positive("radius");
  p.length = in.positive("length");
  p.chamfer = in.non_negative("chamfer", 0.0);
  if (p.chamfer >= p.radius) fail("chamfer", "must be < radius (" + show(p.radius) + ")", show(p.chamfer));
  if (p.chamfer >= p.length) fail("chamfer", "must be < length (" + show(p.length) + ")", show(p.chamfer));
  return p;
}

procedural::HoleBlockParams read_hole_block(const Params& in) {
  in.check_names({"peg_radius", "clearance", "hole_depth", "width", "height", "chamfer", "segments"}, {});
  procedural::HoleBlockParams p;
  p.segments = in.segments();
  p.peg_radius = in.positive("peg_radius");
  p.clearance = in.non_negative("clearance", 0.0);
  p.height = in.positive("height");
  p.hole_depth = in.positive("hole_depth");
  if (p.hole_depth > p.height) fail("hole_depth", "must be <= height (" + show(p.height) + ")", show(p.hole_depth));
  p.chamfer = in.non_negative("chamfer", 0.0);
  if (p.chamfer >= p.hole_depth) fail("chamfer", "must be < hole_depth (" + show(p.hole_depth) + ")", show(p.chamfer));
  p.width = in.positive("width");
  // The entry ring (circumradius hole_radius + chamfer) must leave a wall of at least
  // kMinWallFraction of the half-width to the square's sides.
  const double entry = p.hole_radius() + p.chamfer;
  if (entry > (1.0 - kMinWallFraction) * 0.5 * p.width)
    fail("width",
         "must exceed 2 * (hole circumradius + chamfer) = " + show(2 * entry) + " with a wall of at least " +
             show(100 * kMinWallFraction) +
             "% of the half-width, i.e. be >= " + show(2 * entry / (1.0 - kMinWallFraction)),
         show(p.width));
  return p;
}

procedural::ThreePegParams read_three_peg(const Params& in) {
  in.check_names({"cell", "base_thickness", "cover_thickness", "segments"},
                 {"peg_radii", "peg_heights", "fillet_radii"});
  procedural::ThreePegParams p;
  p.segments = in.segments();
  p.cell = in.positive("cell");
  p.base_thickness = in.positive("base_thickness");
  p.cover_thickness = in.positive("cover_thickness");
  p.peg_radii = in.array3("peg_radii", true, std::nullopt);
  p.peg_heights = in.array3("peg_heights", true, std::nullopt);
  p.fillet_radii = in.array3("fillet_radii", false, 0.0);
  const auto& r = p.peg_radii;
  if (r[0] == r[1] || r[1] == r[2] || r[0] == r[2])
    fail("peg_radii", "entries must be distinct", show(std::vector<double>(r.begin(), r.end())));
  const double room = (1.0 - kMinWallFraction) * 0.5 * p.cell;  // largest r + f in a cell
  for (int k = 0; k < 3; ++k) {
    const std::string idx = "[" + std::to_string(k) + "]";
    const double f = p.fillet_radii[k];
    if (r[k] > room)
      fail("peg_radii" + idx,
           "must be <= " + show(room) + " (cell/2 less a " + show(100 * kMinWallFraction) + "% wall)", show(r[k]));
    if (r[k] + f > room)
      fail("fillet_radii" + idx,
           "peg radius + fillet radius must be <= " + show(room) + " (cell/2 less a " + show(100 * kMinWallFraction) +
               "% wall)",
           show(f));
    if (f >= p.peg_heights[k])
      fail("fillet_radii" + idx, "must be < peg_heights" + idx + " (" + show(p.peg_heights[k]) + ")", show(f));
  }
  return p;
}

}  // namespace

void check_procedural_spec(const ProceduralPartSpec& spec) {
  const Params in{spec};
  if (spec.type == "peg")
    read_peg(in);
  else if (spec.type == "hole_block")
    read_hole_block(in);
  else if (spec.type == "three_peg_base" || spec.type == "three_peg_cover")
    read_three_peg(in);
  else
    fail("type", "unknown procedural part type, expected peg, hole_block, three_peg_base or three_peg_cover",
         "\"" + spec.type + "\"");
}

Mesh make_procedural_part(const ProceduralPartSpec& spec) {
  check_procedural_spec(spec);
  const Params in{spec};
  if (spec.type == "peg") return procedural::make_peg(read_peg(in));
  if (spec.type == "hole_block") return procedural::make_hole_block(read_hole_block(in));
  if (spec.type == "three_peg_base") return procedural::make_three_peg_base(read_three_peg(in));
  return procedural::make_three_peg_cover(read_three_peg(in));
}

std::vector<AnalyticFace> procedural_part_faces(const ProceduralPartSpec& spec) {
  check_procedural_spec(spec);
  const Params in{spec};
  if (spec.type == "peg") return procedural::peg_faces(read_peg(in));
  if (spec.type == "hole_block") return procedural::hole_block_faces(read_hole_block(in));
  if (spec.type == "three_peg_base") return procedural::three_peg_base_faces(read_three_peg(in));
  return procedural::three_peg_cover_faces(read_three_peg(in));
}

}  // namespace snapfit
