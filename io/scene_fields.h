#pragma once
// The scene format's one description: each section's fields with their types, defaults,
// allowed values and meanings (io/scene_fields.cpp). The reader (io/scene_file.cpp)
// takes each section's allowed keys from its table and reads its plain fields through
// it, the writer writes them back through it, and docs/scenes.md's field tables are
// printed from it (scene_fields_markdown; tests/test_scene_schema.cpp checks the docs).
// Fields that need code of their own (poses, parts, the region, keyframes) are listed
// with their docs and read and written by hand.
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include "io/scene_json.h"
#include "snapfit/scene.h"

namespace snapfit::scene_schema {

using scene_json::Ctx;
using json = nlohmann::json;
using ordered_json = nlohmann::ordered_json;

// The numbers a field allows: from `low` to `high`, either end open; whole numbers only
// when `integer`. `why`, when set, follows the range in the error message.
struct NumberRange {
  double low = -std::numeric_limits<double>::infinity(), high = std::numeric_limits<double>::infinity();
  bool low_open = false, high_open = false, integer = false;
  const char* why = nullptr;

  bool holds(double x) const;
  std::string text() const;  // "> 0", ">= 0", "<= 8", "in (0, 1]", "an integer in [0, 16]"; "" for any number
};
NumberRange any_number();
NumberRange above(double low);     // > low
NumberRange at_least(double low);  // >= low
// From low to high; `ends` spells the two ends: "()", "(]", "[)" or "[]".
NumberRange within(double low, double high, const char* ends, const char* why = nullptr);
NumberRange whole_numbers(int low, int high);  // an integer in [low, high]

// A string field whose names stand for an enum's values (core/name_table.h tables).
template <typename T>
struct Choice {
  const char* (*get)(const T&);
  bool (*set)(T&, const std::string&);  // false for an unknown name
  std::string (*names)();               // "a, b or c"
};

// How a field's value is held in its section's struct T; std::monostate: read and
// written by hand (the caller).
template <typename T>
using Binding = std::variant<std::monostate, double T::*, std::optional<double> T::*, int T::*, std::optional<int> T::*,
                             bool T::*, std::string T::*, std::optional<std::string> T::*, Choice<T>>;

template <typename T>
struct Field {
  std::string name;
  Binding<T> value;
  NumberRange range;         // numbers
  std::string meaning;       // the docs' text after the range
  std::string default_text;  // the docs' default where T{} holds none (optional or derived); "" : T{}'s value
  std::string type_text;     // the docs' type of a field read by hand
  bool non_empty = false;    // strings: "" is refused
  // Whether the field may be given, seen after the fields before it are read (null:
  // always); `only_for` says when it may: `kind "skeletal_density"`.
  bool (*applies)(const T&) = nullptr;
  std::string only_for;

  Field when(bool (*condition)(const T&), std::string for_what) const {
    Field f = *this;
    f.applies = condition, f.only_for = std::move(for_what);
    return f;
  }
};

// A field held in member `m`.
template <typename T, typename M>
Field<T> field(const char* name, M T::*m, NumberRange range, const char* meaning, const char* default_text = "") {
  Field<T> f;
  f.name = name, f.value = m, f.range = range, f.meaning = meaning, f.default_text = default_text;
  return f;
}
template <typename T, typename M>
Field<T> field(const char* name, M T::*m, const char* meaning, const char* default_text = "") {
  return field(name, m, any_number(), meaning, default_text);
}
template <typename T>
Field<T> choice(const char* name, Choice<T> c, const char* meaning) {
  Field<T> f;
  f.name = name, f.value = c, f.meaning = meaning;
  return f;
}
// A field the caller reads and writes; `default_text` "required" marks a required one.
template <typename T>
Field<T> by_hand(const char* name, const char* type, const char* default_text, const char* meaning) {
  Field<T> f;
  f.name = name, f.type_text = type, f.default_text = default_text, f.meaning = meaning;
  return f;
}

// The tables, in the docs' order; each section's name is its path in a scene ("part"
// for part1 and part2, "keyframe" for trajectory.keyframes[i], "top" for the top level).
const std::vector<Field<Scene>>& top_fields();
const std::vector<Field<PartSpec>>& part_fields();
const std::vector<Field<PartDescriptorSpec>>& part_descriptor_fields();
const std::vector<Field<CadPartSpec>>& cad_fields();
const std::vector<Field<Pose>>& pose_fields();
const std::vector<Field<Pose>>& rotation_fields();
const std::vector<Field<DescriptorParams>>& descriptor_fields();
const std::vector<Field<GridParams>>& grid_fields();
const std::vector<Field<Scene>>& frame_fields();
const std::vector<Field<Trajectory>>& trajectory_fields();
const std::vector<Field<Keyframe>>& keyframe_fields();
const std::vector<Field<HapticsParams>>& haptics_fields();
const std::vector<Field<VpsParams>>& vps_fields();
const std::vector<Field<VpsHybridParams>>& vps_hybrid_fields();

template <typename T>
std::vector<std::string> names_of(const std::vector<Field<T>>& table) {
  std::vector<std::string> names;
  for (const Field<T>& f : table) names.push_back(f.name);
  return names;
}

// Reads a section: refuses keys not in `table`, then reads each bound field `v` holds
// into `out`, in the table's order (a field's `applies` sees those before it). Fields
// read by hand are left to the caller.
template <typename T>
void read_fields(const Ctx& c, const json& v, const std::string& path, const std::vector<Field<T>>& table, T& out);

// Writes a section's fields in the table's order: bound ones from `in` (an unset
// optional, or a field that does not apply, not at all), those by hand from `by_hand`
// (left out when it lacks them).
template <typename T>
ordered_json write_fields(const std::vector<Field<T>>& table, const T& in,
                          const ordered_json& by_hand = ordered_json::object());

// ---------------------------------------------------------------- the templates

namespace detail {
template <typename>
inline constexpr bool kAlwaysFalse = false;

double read_number(const Ctx& c, const json& v, const std::string& path, const NumberRange& range);
std::string read_text(const Ctx& c, const json& v, const std::string& path, bool non_empty);
[[noreturn]] void fail_unknown_name(const Ctx& c, const std::string& path, const std::string& field,
                                    const std::string& name, const std::string& names);
}  // namespace detail

template <typename T>
void read_fields(const Ctx& c, const json& v, const std::string& path, const std::vector<Field<T>>& table, T& out) {
  scene_json::check_fields(c, v, path, names_of(table));
  for (const Field<T>& f : table) {
    const json* x = scene_json::find(v, f.name.c_str());
    if (!x || std::holds_alternative<std::monostate>(f.value)) continue;
    const std::string p = scene_json::join(path, f.name);
    if (f.applies && !f.applies(out)) scene_json::fail(c, p, "only for " + f.only_for);
    std::visit(
        [&](auto&& m) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, std::monostate>) {
          } else if constexpr (std::is_same_v<M, double T::*> || std::is_same_v<M, std::optional<double> T::*>) {
            out.*m = detail::read_number(c, *x, p, f.range);
          } else if constexpr (std::is_same_v<M, int T::*> || std::is_same_v<M, std::optional<int> T::*>) {
            out.*m = int(detail::read_number(c, *x, p, f.range));
          } else if constexpr (std::is_same_v<M, bool T::*>) {
            out.*m = scene_json::flag(c, *x, p);
          } else if constexpr (std::is_same_v<M, std::string T::*> ||
                               std::is_same_v<M, std::optional<std::string> T::*>) {
            out.*m = detail::read_text(c, *x, p, f.non_empty);
          } else if constexpr (std::is_same_v<M, Choice<T>>) {
            const std::string name = scene_json::text(c, *x, p);
            if (!m.set(out, name)) detail::fail_unknown_name(c, p, f.name, name, m.names());
          } else {
            static_assert(detail::kAlwaysFalse<M>, "a binding without a reader");
          }
        },
        f.value);
  }
}

template <typename T>
ordered_json write_fields(const std::vector<Field<T>>& table, const T& in, const ordered_json& by_hand) {
  ordered_json out = ordered_json::object();
  for (const Field<T>& f : table) {
    if (f.applies && !f.applies(in)) continue;
    std::visit(
        [&](auto&& m) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, std::monostate>) {
            if (by_hand.contains(f.name)) out[f.name] = by_hand[f.name];
          } else if constexpr (std::is_same_v<M, Choice<T>>) {
            out[f.name] = m.get(in);
          } else {
            const auto& value = in.*m;
            using V = std::decay_t<decltype(value)>;
            if constexpr (std::is_same_v<V, std::optional<double>> || std::is_same_v<V, std::optional<int>> ||
                          std::is_same_v<V, std::optional<std::string>>) {
              if (value) out[f.name] = *value;
            } else {
              out[f.name] = value;
            }
          }
        },
        f.value);
  }
  return out;
}

}  // namespace snapfit::scene_schema
