// The scene format's fields, section by section: the one description that the reader,
// the writer and docs/scenes.md's tables share (io/scene_fields.h).
#include "io/scene_fields.h"

#include <cmath>

#include "snapfit/error.h"

namespace snapfit::scene_schema {

using scene_json::fmt;

// ---------------------------------------------------------------- ranges

bool NumberRange::holds(double x) const {
  if (integer && x != std::floor(x)) return false;
  const bool above_low = low_open ? x > low : x >= low;
  const bool below_high = high_open ? x < high : x <= high;
  return above_low && below_high;
}

std::string NumberRange::text() const {
  const bool bounded_low = std::isfinite(low), bounded_high = std::isfinite(high);
  std::string t;
  if (bounded_low && bounded_high)
    t = std::string("in ") + (low_open ? "(" : "[") + fmt(low) + ", " + fmt(high) + (high_open ? ")" : "]");
  else if (bounded_low)
    t = (low_open ? "> " : ">= ") + fmt(low);
  else if (bounded_high)
    t = (high_open ? "< " : "<= ") + fmt(high);
  if (integer) t = "an integer" + (t.empty() ? "" : " " + t);
  return t;
}

NumberRange any_number() { return {}; }
NumberRange above(double low) {
  NumberRange r;
  r.low = low, r.low_open = true;
  return r;
}
NumberRange at_least(double low) {
  NumberRange r;
  r.low = low;
  return r;
}
NumberRange within(double low, double high, const char* ends, const char* why) {
  NumberRange r;
  r.low = low, r.high = high, r.low_open = ends[0] == '(', r.high_open = ends[1] == ')', r.why = why;
  return r;
}
NumberRange whole_numbers(int low, int high) {
  NumberRange r = within(low, high, "[]");
  r.integer = true;
  return r;
}

namespace detail {

double read_number(const Ctx& c, const json& v, const std::string& path, const NumberRange& range) {
  const double x = scene_json::number(c, v, path);
  if (!range.holds(x))
    scene_json::fail(
        c, path,
        "must be " + range.text() + (range.why ? std::string(": ") + range.why : "") + " (got " + fmt(x) + ")");
  return x;
}

std::string read_text(const Ctx& c, const json& v, const std::string& path, bool non_empty) {
  std::string t = scene_json::text(c, v, path);
  if (non_empty && t.empty()) scene_json::fail(c, path, "must not be empty");
  return t;
}

void fail_unknown_name(const Ctx& c, const std::string& path, const std::string& field, const std::string& name,
                       const std::string& names) {
  scene_json::fail(c, path, "unknown " + field + " '" + name + "' (expected " + names + ")");
}

}  // namespace detail

// ---------------------------------------------------------------- the tables

namespace {

// A field whose value must be a non-empty string.
template <typename T>
Field<T> non_empty(Field<T> f) {
  f.non_empty = true;
  return f;
}

// An enum field's choice, through the enum's name table (io/scene_names.cpp).
template <typename T, typename E, E T::*member, const char* (*name)(E), std::optional<E> (*named)(const std::string&)>
Choice<T> enum_choice(std::string (*names)()) {
  return {[](const T& t) { return name(t.*member); },
          [](T& t, const std::string& n) {
            const std::optional<E> value = named(n);
            if (value) t.*member = *value;
            return bool(value);
          },
          names};
}

const char* const kSphereMethods[] = {"auto", "direct", "nufft"};

}  // namespace

const std::vector<Field<Scene>>& top_fields() {
  static const std::vector<Field<Scene>> table = {
      by_hand<Scene>("snapfit_scene", "number", "required", "format version; must be `1`"),
      field("name", &Scene::name, "free text, shown in reports"),
      by_hand<Scene>("units", "string", "required",
                     "length unit of the scene: `um`, `mm`, `cm`, `m`, `km`, `in` (case-sensitive)"),
      by_hand<Scene>("part1", "[part](#part)", "required", "the fixed part, the frame of reference"),
      by_hand<Scene>("part2", "[part](#part)", "required", "the moving part, held by the haptic device"),
      by_hand<Scene>("assembled_pose", "[pose](#pose)", "none",
                     "part 2 relative to part 1 when assembled (used for reports and error maps)"),
      by_hand<Scene>("descriptor", "[descriptor](#descriptor)", "all defaults", "shape descriptor and its parameters"),
      by_hand<Scene>("grid", "[grid](#grid)", "required", "where the descriptor fields are sampled"),
      by_hand<Scene>("frame", "[frame](#frame)", "all defaults", "haptic frame budget and loop rate"),
      by_hand<Scene>("outputs", "array of strings", "all the motion allows", "see [outputs](#outputs)"),
      choice<Scene>("motion", enum_choice<Scene, Motion, &Scene::motion, motion_name, motion_named>(motion_names),
                    "`\"translation\"` (part 2 keeps its orientation) or `\"6dof\"`"),
      by_hand<Scene>("trajectory", "[trajectory](#trajectory)", "none", "scripted device poses for unattended runs"),
      by_hand<Scene>("haptics", "[haptics](#haptics)", "all defaults",
                     "virtual coupling, device limits, geometric gain, success test"),
      choice<Scene>("method", enum_choice<Scene, Method, &Scene::method, method_name, method_named>(method_names),
                    "the haptic rendering method of `snapfit run`: `\"snapfit\"`, `\"vps\"` ([Voxmap "
                    "PointShell](#vps)) or `\"vps_hybrid\"` (VPS with geometric constraints, [below](#vps))"),
      by_hand<Scene>("vps", "[vps](#vps)", "all defaults", "Voxmap PointShell's parameters (read whatever the method)"),
  };
  return table;
}

const std::vector<Field<PartSpec>>& part_fields() {
  static const std::vector<Field<PartSpec>> table = {
      field("name", &PartSpec::name, "free text", "`\"part1\"` / `\"part2\"`"),
      by_hand<PartSpec>(
          "mesh", "string", "—",
          "mesh file (any format Assimp reads: STL, OBJ, PLY, glTF, OFF, ...), or a STEP (`.step`, `.stp`) or IGES "
          "(`.iges`, `.igs`) file, read through OpenCASCADE ([CAD parts](#cad-parts)). A relative path is relative to "
          "the folder of the scene file (to the working directory for `parse_scene` with an origin that has no "
          "folder). The file must exist when the scene is read."),
      by_hand<PartSpec>("mesh_units", "string", "the scene's `units`",
                        "unit of the mesh file's coordinates; mesh parts only, not STEP or IGES (they declare theirs)"),
      by_hand<PartSpec>("scale", "number", "`1`", "> 0; extra factor; mesh parts only"),
      by_hand<PartSpec>("cad", "[cad](#cad)", "all defaults",
                        "how a STEP or IGES file is read and tessellated; STEP and IGES parts only"),
      by_hand<PartSpec>("procedural", "[object](#procedural-parts)", "—", "a part generated by snapfit"),
      by_hand<PartSpec>("pose", "[pose](#pose)", "identity",
                        "part 1: its world pose; part 2: its initial pose relative to part 1"),
      by_hand<PartSpec>("descriptor", "[part descriptor](#part-descriptor)", "`{\"source\": \"grid\"}`",
                        "where the part's spectrum comes from"),
  };
  return table;
}

const std::vector<Field<PartDescriptorSpec>>& part_descriptor_fields() {
  using D = PartDescriptorSpec;
  const auto spheres = [](const D& d) { return d.source == SpectrumSource::spheres; };
  static const std::vector<Field<D>> table = {
      choice<D>("source",
                enum_choice<D, SpectrumSource, &D::source, spectrum_source_name, spectrum_source_named>(
                    spectrum_source_names),
                "`\"grid\"` or `\"spheres\"`; `\"spheres\"` needs the scene's `descriptor.kind` `\"indicator\"` (seed "
                "001 defines ball sums for the indicator, not the skeletal density)"),
      field("tolerance", &D::tolerance, above(0),
            "scene units; `spheres` only: the Hausdorff bound epsilon of the decomposition (its grid spacing is 2 "
            "epsilon / sqrt 3)",
            "the grid spacing")
          .when(spheres, "source \"spheres\""),
      field("protrusion", &D::protrusion, within(0, 1, "[]"), "`spheres` only: seed 001's mu (A.1)")
          .when(spheres, "source \"spheres\""),
      choice<D>("method",
                {[](const D& d) { return d.method.c_str(); },
                 [](D& d, const std::string& n) {
                   for (const char* m : kSphereMethods)
                     if (n == m) return d.method = n, true;
                   return false;
                 },
                 [] { return std::string("auto, direct or nufft"); }},
                "`spheres` only: `\"direct\"` (the NDFT on the device, O(balls x modes)), `\"nufft\"` (type-1 "
                "non-uniform FFT) or `\"auto\"` (direct below a measured ball count: 45 balls up to 48^3 lattice "
                "nodes, 181 above; [spheres.md](spheres.md#the-auto-switch))")
          .when(spheres, "source \"spheres\""),
      field("nufft_tolerance", &D::nufft_tolerance, within(0, 0.1, "(]"),
            "`spheres` only: accuracy of the NUFFT relative to the balls' total volume")
          .when(spheres, "source \"spheres\""),
  };
  return table;
}

const std::vector<Field<CadPartSpec>>& cad_fields() {
  static const std::vector<Field<CadPartSpec>> table = {
      non_empty(field("solid", &CadPartSpec::solid,
                      "the solid to take, by the name the file gives it (below); required when the file holds more "
                      "than one",
                      "the only one")),
      field("deflection", &CadPartSpec::deflection, above(0),
            "scene units; the largest distance allowed between the mesh and the B-rep surface (linear deflection)",
            "the grid spacing / 40"),
      field("angular_deflection_deg", &CadPartSpec::angular_deflection_deg, within(0, 90, "(]"),
            "the angular deflection (OpenCASCADE splits a circle into segments of half this angle, so at least 24)",
            "`30`"),
  };
  return table;
}

const std::vector<Field<Pose>>& pose_fields() {
  static const std::vector<Field<Pose>> table = {
      by_hand<Pose>("position", "array of 3 numbers", "`[0, 0, 0]`", "translation t, scene units"),
      by_hand<Pose>("rotation", "[rotation](#rotation)", "identity", "rotation R about the part's own origin"),
  };
  return table;
}

const std::vector<Field<Pose>>& rotation_fields() {
  static const std::vector<Field<Pose>> table = {
      by_hand<Pose>("axis", "array of 3 numbers", "—", "any non-zero length; it is normalised"),
      by_hand<Pose>("angle_deg", "number", "—", "degrees, right-handed about `axis`; any finite value"),
      by_hand<Pose>("quaternion", "array of 4 numbers", "—",
                    "`[w, x, y, z]`; its norm must be within 1e-6 of 1 (absolute), and it is then normalised. A "
                    "larger error is reported rather than silently fixed: it usually means a typo. `q` and `-q` are "
                    "the same rotation."),
  };
  return table;
}

const std::vector<Field<DescriptorParams>>& descriptor_fields() {
  using D = DescriptorParams;
  const auto skeletal = [](const D& d) { return d.kind == DescriptorKind::skeletal_density; };
  static const std::vector<Field<D>> table = {
      choice<D>(
          "kind",
          enum_choice<D, DescriptorKind, &D::kind, descriptor_kind_name, descriptor_kind_named>(descriptor_kind_names),
          "`\"skeletal_density\"`: rho = i lambda s_sigma ([design.md](design.md), seed 000 eq. 2-3). "
          "`\"indicator\"`: the winding number alone, the collision gap function (seed 000 eq. 1)"),
      field("sigma", &D::sigma, above(0),
            "Gaussian width of g_sigma(eta/\\|xi\\| - 1), dimensionless. `skeletal_density` only")
          .when(skeletal, "kind \"skeletal_density\""),
      field("lambda_in", &D::lambda_in, above(0), "affinity factor inside. `skeletal_density` only")
          .when(skeletal, "kind \"skeletal_density\""),
      field("lambda_out", &D::lambda_out, above(0),
            "affinity factor outside; the penalty factor is lambda_in / lambda_out. `skeletal_density` only")
          .when(skeletal, "kind \"skeletal_density\""),
      field("tolerance", &D::tolerance, within(0, 1, "()"),
            "relative error allowed per cluster of the surface integrals (winding number and skeletal density). The "
            "engine reports a rigorous per-point error bound; the measured actual error is about 0.1 x tolerance "
            "relative (tests/test_descriptors.cpp). Smaller is slower: 0.05 costs about 2x, 0.2 about 0.6x the time "
            "of 0.1"),
  };
  return table;
}

const std::vector<Field<GridParams>>& grid_fields() {
  static const std::vector<Field<GridParams>> table = {
      field("spacing", &GridParams::spacing, above(0), "grid spacing, scene units", "—"),
      field("resolution", &GridParams::resolution, whole_numbers(8, 1024),
            "grid points along the longest axis of the padded box (`64.0` is accepted as 64, `64.5` is not)", "—"),
      field("padding", &GridParams::padding, at_least(0),
            "added on every side of the parts' bounding box, scene units"),
      by_hand<GridParams>(
          "region", "string or object", "`\"reach\"`",
          "where part 1's grid, fields, spectra and rigid contact are needed: `\"reach\"`, the box part 2's grid "
          "sweeps along the trajectory (all of part 1 without a trajectory, for `snapfit search` and for `snapfit "
          "serve`, where a person moves the device anywhere); `\"whole\"`, all of part 1; or a workspace `{\"min\": "
          "[x, y, z], \"max\": [x, y, z]}` (part 1's frame, scene units) that part 2's origin stays in, at any "
          "orientation"),
      by_hand<GridParams>("region_margin", "number", "a quarter of part 2's padded diagonal",
                          ">= 0, scene units; added on every side of the region"),
  };
  return table;
}

const std::vector<Field<Scene>>& frame_fields() {
  static const std::vector<Field<Scene>> table = {
      field("budget_ms", &Scene::frame_budget_ms, above(0),
            "time one haptic frame may take; at most the loop period 1000 / `rate_hz`"),
      field("rate_hz", &Scene::loop_rate_hz, above(0), "haptic loop rate"),
  };
  return table;
}

const std::vector<Field<Trajectory>>& trajectory_fields() {
  static const std::vector<Field<Trajectory>> table = {
      by_hand<Trajectory>("keyframes", "array of keyframes (below)", "required", "at least one"),
  };
  return table;
}

const std::vector<Field<Keyframe>>& keyframe_fields() {
  static const std::vector<Field<Keyframe>> table = {
      by_hand<Keyframe>("time_s", "number", "required", "seconds; the first >= 0, then strictly increasing"),
      by_hand<Keyframe>("position", "array of 3 numbers", "`[0, 0, 0]`",
                        "device position of part 2, relative to part 1"),
      by_hand<Keyframe>("rotation", "[rotation](#rotation)", "identity",
                        "device orientation of part 2, relative to part 1"),
  };
  return table;
}

const std::vector<Field<HapticsParams>>& haptics_fields() {
  using H = HapticsParams;
  static const std::vector<Field<H>> table = {
      field("mass_kg", &H::mass_kg, above(0),
            "the proxy's mass; its inertia is isotropic, (2/3) m <\\|q\\|^2> of part 2's solid about its frame origin"),
      field("stiffness_n_per_m", &H::stiffness_n_per_m, above(0), "coupling k_T"),
      field("rot_stiffness_nm_per_rad", &H::rot_stiffness_nm_per_rad, above(0),
            "coupling k_R (r_g: part 2's radius of gyration about its origin)", "k_T r_g^2"),
      field("damping_ratio", &H::damping_ratio, at_least(0), "1 = critically damped, b = 2 sqrt(k m) for both"),
      field("max_force_n", &H::max_force_n, above(0), "the device's force limit"),
      field("max_torque_nm", &H::max_torque_nm, at_least(0), "the device's torque limit; 0 = no torque output"),
      field("geometry_gain", &H::geometry_gain, at_least(0), "N per engine force unit", "from `geometry_strength`"),
      field("geometry_strength", &H::geometry_strength, at_least(0),
            "default gain = strength k_T h / F_probe, with F_probe the largest engine force 2 h off the assembled pose "
            "along the axes: the fit then feels about strength/2 times as stiff as the coupling"),
      field("settle_s", &H::settle_s, at_least(0), "loop time after the last keyframe in `snapfit run`"),
      field("success_position", &H::success_position, above(0),
            "final position error (scene units) that counts as assembled, with the angle; part 2's surface within "
            "this of where the assembled pose puts it counts too, at any angle "
            "([haptics.md](haptics.md#assembled-or-not))",
            "grid spacing h"),
      field("success_angle_deg", &H::success_angle_deg, above(0),
            "final angle error that counts as assembled, with the position"),
      field("contact", &H::contact,
            "the rigid contact between the parts' surfaces ([haptics.md](haptics.md#rigid-contact)); `false` renders "
            "seed 000's energy alone"),
      field("contact_stiffness_n_per_mm3", &H::contact_stiffness_n_per_mm3, above(0),
            "contact pressure (N/mm^2) per mm of interpenetration"),
      field("contact_spacing", &H::contact_spacing, above(0),
            "the contact's surface samples (scene units); its distance grid is at a third of it", "grid spacing h"),
      field("max_force_rate_n_per_s", &H::max_force_rate_n_per_s, at_least(0),
            "the most the force sent may change per second (0.2 N between 1 kHz frames); a frame that would change it "
            "faster damps the part instead; 0: no bound. VPS runs without it"),
      field("vouch", &H::vouch,
            "render seed 000's wrench only as far as the query's own error estimate vouches for it "
            "([haptics.md](haptics.md#a-wrench-the-engine-can-vouch-for)); `false` renders it whole"),
  };
  return table;
}

const std::vector<Field<VpsParams>>& vps_fields() {
  using V = VpsParams;
  static const std::vector<Field<V>> table = {
      field("voxel_size", &V::voxel_size, above(0), "part 1's voxels, scene units", "grid spacing h"),
      field("stiffness_n_per_m", &V::stiffness_n_per_m, above(0), "k_ff, the penalty stiffness of one shell point"),
      field("shell_density", &V::shell_density, within(0, 8, "(]"),
            "shell points per voxel along the surface (shell spacing = voxel_size / density)"),
      field("proximity_layers", &V::proximity_layers, whole_numbers(0, 16),
            "free voxel layers around part 1 whose points get the pre-contact braking"),
      field("braking_n_s_per_m", &V::braking_n_s_per_m, at_least(0),
            "b_ff, the braking of one approaching point (m: `haptics.mass_kg`)", "2 sqrt(k_ff m) / 10"),
      by_hand<V>("hybrid", "[vps hybrid](#vps-hybrid)", "all defaults",
                 "the VPS - constraint hybrid's parameters (`\"method\": \"vps_hybrid\"`)"),
  };
  return table;
}

const std::vector<Field<VpsHybridParams>>& vps_hybrid_fields() {
  using H = VpsHybridParams;
  static const std::vector<Field<H>> table = {
      field("alignment_fraction", &H::alignment_fraction,
            within(0, 1, "()", "the user stays stronger than the constraint"),
            "k_A, the alignment spring (eq. 18), as this fraction of the coupling's translational stiffness (seed 002 "
            "5.4)"),
      field("rotation_fraction", &H::rotation_fraction,
            within(0, 1, "()", "the user stays stronger than the constraint"),
            "k_R, the rotational alignment spring, as this fraction of the coupling's rotational stiffness (the "
            "paper's: 0.5)"),
      field("x_engage", &H::x_engage, within(0, 1, "(]"),
            "a recognised constraint engages when its x (eq. 15) reaches this"),
      field("x_release", &H::x_release, within(0, 1, "(]"),
            "below `x_engage`; an engaged constraint releases when x falls below this (hysteresis)"),
      field("x_full", &H::x_full, within(0, 1, "(]"),
            "the blend weight is min(1, x / `x_full`) times the ramp: `1` is eq. 13's x itself (the paper's); below "
            "1 the weight saturates at 1 once x reaches it"),
      field("ramp_s", &H::ramp_s, at_least(0), "seconds to phase a constraint in or out"),
      field("radius_tolerance", &H::radius_tolerance, above(0),
            "the largest \\|r1 - r2\\| of a concentric pair, scene units", "2 voxels"),
      field("offset_tolerance", &H::offset_tolerance, above(0),
            "the largest axis offset beyond \\|r1 - r2\\| (concentric) or plane separation (planar), scene units",
            "2 voxels"),
      field("angle_tolerance_deg", &H::angle_tolerance_deg, within(0, 90, "(]"),
            "the largest angle between the axes, or between one normal and the other's opposite", "11.46 (0.2 rad)"),
      choice<H>("region",
                enum_choice<H, HybridRegion, &H::region, hybrid_region_name, hybrid_region_named>(hybrid_region_names),
                "the contacts whose collision force a constraint blends out: `\"pair\"` (the paper's), those between "
                "its two faces and between one of them and an edge; `\"face\"`, every contact whose voxel lies on its "
                "face of part 1 or whose point lies on its face of part 2"),
  };
  return table;
}

// ---------------------------------------------------------------- the docs

namespace {

template <typename T>
std::string type_of(const Field<T>& f) {
  if (!f.type_text.empty()) return f.type_text;
  return std::visit(
      [](auto&& m) -> std::string {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, double T::*> || std::is_same_v<M, std::optional<double> T::*>)
          return "number";
        else if constexpr (std::is_same_v<M, int T::*> || std::is_same_v<M, std::optional<int> T::*>)
          return "integer";
        else if constexpr (std::is_same_v<M, bool T::*>)
          return "boolean";
        else
          return "string";
      },
      f.value);
}

// The default that T{} holds, as the docs write it.
template <typename T>
std::string default_of(const Field<T>& f) {
  if (!f.default_text.empty()) return f.default_text;
  const T defaults{};
  return std::visit(
      [&](auto&& m) -> std::string {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, std::monostate>) {
          throw Error("scene field '" + f.name + "' is read by hand and has no default text");
        } else if constexpr (std::is_same_v<M, Choice<T>>) {
          return "`\"" + std::string(m.get(defaults)) + "\"`";
        } else {
          using V = std::decay_t<decltype(defaults.*m)>;
          if constexpr (std::is_same_v<V, double> || std::is_same_v<V, int>)
            return "`" + fmt(double(defaults.*m)) + "`";
          else if constexpr (std::is_same_v<V, bool>)
            return defaults.*m ? "`true`" : "`false`";
          else if constexpr (std::is_same_v<V, std::string>)
            return "`\"" + defaults.*m + "\"`";
          else
            throw Error("scene field '" + f.name + "' is optional and has no default text");
        }
      },
      f.value);
}

template <typename T>
void add_section(std::vector<SceneFieldInfo>& out, const char* section, const std::vector<Field<T>>& table) {
  for (const Field<T>& f : table) {
    const std::string range = f.range.text() + (f.range.why ? std::string(": ") + f.range.why : "");
    out.push_back({section, f.name, type_of(f), default_of(f), range.empty() ? f.meaning : range + "; " + f.meaning});
  }
}

}  // namespace

}  // namespace snapfit::scene_schema

namespace snapfit {

std::vector<SceneFieldInfo> scene_fields() {
  using namespace scene_schema;
  std::vector<SceneFieldInfo> out;
  add_section(out, "top", top_fields());
  add_section(out, "part", part_fields());
  add_section(out, "part.descriptor", part_descriptor_fields());
  add_section(out, "cad", cad_fields());
  add_section(out, "pose", pose_fields());
  add_section(out, "rotation", rotation_fields());
  add_section(out, "descriptor", descriptor_fields());
  add_section(out, "grid", grid_fields());
  add_section(out, "frame", frame_fields());
  add_section(out, "trajectory", trajectory_fields());
  add_section(out, "keyframe", keyframe_fields());
  add_section(out, "haptics", haptics_fields());
  add_section(out, "vps", vps_fields());
  add_section(out, "vps.hybrid", vps_hybrid_fields());
  return out;
}

std::vector<std::string> scene_field_sections() {
  std::vector<std::string> sections;
  for (const SceneFieldInfo& f : scene_fields())
    if (sections.empty() || sections.back() != f.section) sections.push_back(f.section);
  return sections;
}

std::string scene_fields_markdown(const std::string& section) {
  std::string table = "| Field | Type | Default | Constraint / meaning |\n|---|---|---|---|\n";
  bool any = false;
  for (const SceneFieldInfo& f : scene_fields()) {
    if (f.section != section) continue;
    table += "| `" + f.name + "` | " + f.type + " | " + f.default_value + " | " + f.meaning + " |\n";
    any = true;
  }
  if (!any) {
    std::string known;
    for (const std::string& s : scene_field_sections()) known += (known.empty() ? "" : ", ") + s;
    throw Error("scene_fields_markdown: unknown section '" + section + "' (the sections: " + known + ")");
  }
  return table;
}

}  // namespace snapfit
