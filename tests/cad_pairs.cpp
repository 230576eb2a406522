// The six CAD pairs of tests/cad_pairs.h, modelled with OpenCASCADE.
#include "tests/cad_pairs.h"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepFilletAPI_MakeChamfer.hxx>
#include <BRepFilletAPI_MakeFillet.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Tool.hxx>
#include <TopExp.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "tests/cad_shape_writer.h"
#include "tests/merged_faces.h"

namespace snapfit::test {
namespace {

constexpr double kEps = 1e-6;

TopoDS_Shape cylinder(double r, double z0, double z1, double x = 0, double y = 0) {
  return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, z0), gp_Dir(0, 0, 1)), r, z1 - z0).Shape();
}

TopoDS_Shape box(double x0, double y0, double z0, double x1, double y1, double z1) {
  return BRepPrimAPI_MakeBox(gp_Pnt(x0, y0, z0), gp_Pnt(x1, y1, z1)).Shape();
}

TopoDS_Shape fuse(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Fuse(a, b).Shape(); }
TopoDS_Shape cut(const TopoDS_Shape& a, const TopoDS_Shape& b) { return BRepAlgoAPI_Cut(a, b).Shape(); }

// The edges of `shape` that `keep` accepts, each once.
std::vector<TopoDS_Edge> edges_where(const TopoDS_Shape& shape, const std::function<bool(const BRepAdaptor_Curve&)>& keep) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, TopAbs_EDGE, map);
  std::vector<TopoDS_Edge> out;
  for (int i = 1; i <= map.Extent(); ++i) {
    const TopoDS_Edge e = TopoDS::Edge(map(i));
    if (BRep_Tool::Degenerated(e)) continue;
    if (keep(BRepAdaptor_Curve(e))) out.push_back(e);
  }
  return out;
}

// Circles (or arcs) of radius r centred on the axis x = cx, y = 0 in the plane z.
std::vector<TopoDS_Edge> circles(const TopoDS_Shape& shape, double r, double z, double cx = 0) {
  return edges_where(shape, [&](const BRepAdaptor_Curve& c) {
    if (c.GetType() != GeomAbs_Circle) return false;
    const gp_Circ circle = c.Circle();
    const gp_Pnt o = circle.Location();
    return std::abs(circle.Radius() - r) < kEps && std::abs(o.Z() - z) < kEps && std::abs(o.X() - cx) < kEps &&
           std::abs(o.Y()) < kEps;
  });
}

// Straight edges in the plane z whose midpoint lies within `reach` of the z axis.
std::vector<TopoDS_Edge> lines(const TopoDS_Shape& shape, double z, double reach) {
  return edges_where(shape, [&](const BRepAdaptor_Curve& c) {
    if (c.GetType() != GeomAbs_Line) return false;
    const gp_Pnt a = c.Value(c.FirstParameter()), b = c.Value(c.LastParameter());
    const double mx = 0.5 * (a.X() + b.X()), my = 0.5 * (a.Y() + b.Y());
    return std::abs(a.Z() - z) < kEps && std::abs(b.Z() - z) < kEps && std::hypot(mx, my) < reach;
  });
}

TopoDS_Shape fillet(const TopoDS_Shape& shape, const std::vector<TopoDS_Edge>& edges, double r) {
  if (edges.empty()) throw std::runtime_error("cad pair: no edge to fillet");
  BRepFilletAPI_MakeFillet make(shape);
  for (const TopoDS_Edge& e : edges) make.Add(r, e);
  return make.Shape();
}

TopoDS_Shape chamfer(const TopoDS_Shape& shape, const std::vector<TopoDS_Edge>& edges, double d) {
  if (edges.empty()) throw std::runtime_error("cad pair: no edge to chamfer");
  BRepFilletAPI_MakeChamfer make(shape);
  for (const TopoDS_Edge& e : edges) make.Add(d, e);
  return make.Shape();
}

struct Parts {
  TopoDS_Shape part1, part2;
};

Parts screw_rod() {
  const ScrewRodDims d;
  const double L = d.rod_half_length, t = d.rod_thickness;
  TopoDS_Shape head = cylinder(d.head_radius, 0, d.head_height);
  head = fillet(head, circles(head, d.head_radius, d.head_height), d.head_fillet);
  TopoDS_Shape shank = cylinder(d.shank_radius, -d.shank_length, 0);
  shank = chamfer(shank, circles(shank, d.shank_radius, -d.shank_length), d.tip_chamfer);
  TopoDS_Shape rod = box(-L, -d.rod_width / 2, -t, L, d.rod_width / 2, 0);
  for (double x : {-L, L}) rod = fuse(rod, cylinder(d.rod_width / 2, -t, 0, x));
  for (double x : {-L, L}) rod = cut(rod, cylinder(d.hole_radius, -t - 1, 1, x));
  return {merged_faces(rod), merged_faces(fuse(head, shank))};
}

Parts ring_shaft() {
  const RingShaftDims d;
  TopoDS_Shape shaft = cylinder(d.shaft_radius, 0, d.shaft_length);
  shaft = chamfer(shaft, circles(shaft, d.shaft_radius, d.shaft_length), d.shaft_chamfer);
  shaft = fuse(cylinder(d.shoulder_radius, -d.shoulder_height, 0), shaft);
  TopoDS_Shape ring = cut(cylinder(d.ring_outer, 0, d.ring_height), cylinder(d.ring_inner, -1, d.ring_height + 1));
  std::vector<TopoDS_Edge> bore = circles(ring, d.ring_inner, 0);
  for (const TopoDS_Edge& e : circles(ring, d.ring_inner, d.ring_height)) bore.push_back(e);
  return {merged_faces(shaft), merged_faces(chamfer(ring, bore, d.bore_chamfer))};
}

Parts square_peg() {
  const SquarePegDims d;
  const double s = d.peg_side / 2, h = s + d.clearance, b = d.block_side / 2;
  TopoDS_Shape peg = box(-s, -s, 0, s, s, d.peg_length);
  peg = chamfer(peg, lines(peg, 0, d.peg_side), d.peg_chamfer);
  TopoDS_Shape block = cut(box(-b, -b, -d.block_height, b, b, 0), box(-h, -h, -d.hole_depth, h, h, 1));
  block = chamfer(block, lines(block, 0, h + kEps), d.entry_chamfer);
  return {merged_faces(block), merged_faces(peg)};
}

// A D: the cylinder of radius r from z0 to z1 less everything beyond x = flat.
TopoDS_Shape d_profile(double r, double flat, double z0, double z1) {
  return cut(cylinder(r, z0, z1), box(flat, -r - 1, z0 - 1, r + 1, r + 1, z1 + 1));
}

Parts d_shaft() {
  const DShaftDims d;
  const double b = d.block_side / 2;
  const TopoDS_Shape hole = d_profile(d.radius + d.clearance, d.flat + d.clearance, -d.hole_depth, 1);
  const TopoDS_Shape block = cut(box(-b, -b, -d.block_height, b, b, 0), hole);
  return {merged_faces(block), merged_faces(d_profile(d.radius, d.flat, 0, d.length))};
}

Parts two_pins() {
  const TwoPinDims d;
  const double lx = d.plate_length / 2, wy = d.plate_width / 2;
  TopoDS_Shape plate = box(-lx, -wy, 0, lx, wy, d.plate_thickness);
  TopoDS_Shape block = box(-lx, -wy, -d.block_height, lx, wy, 0);
  for (double x : {-d.pin_offset, d.pin_offset}) {
    TopoDS_Shape pin = cylinder(d.pin_radius, -d.pin_length, 0, x);
    pin = chamfer(pin, circles(pin, d.pin_radius, -d.pin_length, x), d.pin_chamfer);
    plate = fuse(plate, pin);
    block = cut(block, cylinder(d.pin_radius + d.clearance, -d.hole_depth, 1, x));
  }
  return {merged_faces(block), merged_faces(plate)};
}

Parts grooved_shaft() {
  const GroovedShaftDims d;
  TopoDS_Shape shank = cylinder(d.shaft_radius, -d.shaft_length, 0);
  shank = fillet(shank, circles(shank, d.shaft_radius, -d.shaft_length), d.tip_fillet);
  const double r_in = d.shaft_radius - d.groove_depth;
  const TopoDS_Shape groove = cut(cylinder(d.shaft_radius + 1, d.groove_top - d.groove_width, d.groove_top),
                                  cylinder(r_in, d.groove_top - d.groove_width - 1, d.groove_top + 1));
  shank = cut(shank, groove);
  TopoDS_Shape head = cylinder(d.head_radius, 0, d.head_height);
  head = fillet(head, circles(head, d.head_radius, d.head_height), d.head_fillet);
  const double bore = d.shaft_radius + d.clearance;
  TopoDS_Shape collar =
      cut(cylinder(d.collar_outer, -d.collar_height, 0), cylinder(bore, -d.collar_height - 1, 1));
  collar = chamfer(collar, circles(collar, bore, 0), d.entry_chamfer);
  return {merged_faces(collar), merged_faces(fuse(shank, head))};
}

Parts make_pair(const std::string& name) {
  if (name == "screw_rod") return screw_rod();
  if (name == "ring_shaft") return ring_shaft();
  if (name == "square_peg") return square_peg();
  if (name == "d_shaft") return d_shaft();
  if (name == "two_pins") return two_pins();
  if (name == "grooved_shaft") return grooved_shaft();
  throw std::runtime_error("cad pair: unknown pair " + name);
}

// JSON as the shipped scenes are written: a value on one line when it fits in 110
// characters (with a space after each colon and comma), else one member or element a line.
std::string inline_json(const nlohmann::ordered_json& j) {
  if (!j.is_structured()) return j.dump();
  std::string out = j.is_object() ? "{" : "[";
  for (auto it = j.begin(); it != j.end(); ++it) {
    if (it != j.begin()) out += ", ";
    if (j.is_object()) out += nlohmann::json(it.key()).dump() + ": ";
    out += inline_json(*it);
  }
  return out + (j.is_object() ? "}" : "]");
}

void write_json(std::string& out, const nlohmann::ordered_json& j, int indent) {
  const std::string flat = inline_json(j);
  if (flat.size() + indent <= 110 || !j.is_structured()) {
    out += flat;
    return;
  }
  const std::string pad(indent + 2, ' ');
  out += j.is_object() ? "{\n" : "[\n";
  std::size_t k = 0;
  for (auto it = j.begin(); it != j.end(); ++it, ++k) {
    out += pad;
    if (j.is_object()) out += nlohmann::json(it.key()).dump() + ": ";
    write_json(out, *it, indent + 2);
    out += k + 1 < j.size() ? ",\n" : "\n";
  }
  out += std::string(indent, ' ') + (j.is_object() ? "}" : "]");
}

nlohmann::ordered_json position(const Eigen::Vector3d& p) { return {p.x(), p.y(), p.z()}; }

nlohmann::ordered_json keyframe(double time, const Eigen::Vector3d& p, double tilt_deg) {
  return {{"time_s", time}, {"position", position(p)}, {"rotation", {{"axis", {0, 1, 0}}, {"angle_deg", tilt_deg}}}};
}

}  // namespace

const std::vector<CadPairInfo>& cad_pairs() {
  static const std::vector<CadPairInfo> pairs = [] {
    const ScrewRodDims s;
    const RingShaftDims r;
    const SquarePegDims q;
    const DShaftDims d;
    const TwoPinDims p;
    const GroovedShaftDims g;
    return std::vector<CadPairInfo>{
        {"screw_rod", "cheese-head screw through a link rod, 1 mm clearance, head seated on the rod", "rod", "screw",
         s.hole_radius - s.shank_radius, s.shank_length, s.rod_thickness, 0.6, {s.rod_half_length, 0, 0}},
        {"ring_shaft", "ring slid 110 mm down a shaft to its shoulder, zero clearance", "shaft", "ring",
         r.ring_inner - r.shaft_radius, r.shaft_length, r.ring_height, 0.6, {0, 0, 0}},
        {"square_peg", "square peg in a blind square hole, 0.1 mm clearance", "block", "peg", q.clearance,
         q.hole_depth, q.hole_depth, 0.6, {0, 0, -q.hole_depth}},
        {"d_shaft", "D-shaft in a blind D-hole, 0.2 mm clearance", "block", "shaft", d.clearance, d.hole_depth,
         d.hole_depth, 0.6, {0, 0, -d.hole_depth}},
        {"two_pins", "plate with two pins into two holes, 0.05 mm clearance", "block", "plate", p.clearance,
         p.pin_length, p.pin_length, 0.6, {0, 0, 0}},
        {"grooved_shaft", "filleted, grooved shaft with a head into a chamfered collar, 0.5 mm clearance", "collar",
         "shaft", g.clearance, g.shaft_length, g.collar_height, 0.6, {0, 0, 0}},
    };
  }();
  return pairs;
}

std::vector<std::string> write_cad_pair(const CadPairInfo& pair, const std::string& dir) {
  const Parts parts = make_pair(pair.name);
  std::filesystem::create_directories(dir);
  const std::string f1 = (std::filesystem::path(dir) / (pair.name + "_1.step")).string();
  const std::string f2 = (std::filesystem::path(dir) / (pair.name + "_2.step")).string();
  write_cad_shape(f1, parts.part1, pair.part1);
  write_cad_shape(f2, parts.part2, pair.part2);
  return {f1, f2};
}

std::string cad_pair_scene(const CadPairInfo& pair, const std::string& parts_folder) {
  // Start 8 mm above first contact, 1 mm off the axis and tilted 3 degrees; reach the entry
  // 0.5 mm off at 1.5 degrees; then down at 25 mm/s (at least 1.5 s), upright, to the assembled pose.
  const Eigen::Vector3d a = pair.assembled, up(0, 0, 1);
  const double slide_s = std::max(1.5, pair.entry / 25);
  const Eigen::Vector3d start = a + Eigen::Vector3d(1, 0, 0) + (pair.entry + 8) * up;
  const std::string folder = parts_folder.empty() || parts_folder.back() == '/' ? parts_folder : parts_folder + "/";
  nlohmann::ordered_json j;
  j["snapfit_scene"] = 1;
  j["name"] = pair.title;
  j["units"] = "mm";
  j["part1"] = {{"name", pair.part1}, {"mesh", folder + pair.name + "_1.step"}};
  j["part2"] = {{"name", pair.part2},
                {"mesh", folder + pair.name + "_2.step"},
                {"pose", {{"position", position(start)}, {"rotation", {{"axis", {0, 1, 0}}, {"angle_deg", 3}}}}}};
  j["assembled_pose"] = {{"position", position(a)}};
  j["descriptor"] = {{"kind", "skeletal_density"}, {"sigma", 0.5}, {"lambda_in", 3}, {"lambda_out", 1}, {"tolerance", 0.1}};
  j["grid"] = {{"spacing", pair.spacing}, {"padding", 5}};
  j["frame"] = {{"budget_ms", 1.0}, {"rate_hz", 1000}};
  j["outputs"] = {"energy", "force", "torque"};
  j["motion"] = "6dof";
  j["trajectory"]["keyframes"] = {keyframe(0, start, 3),
                                  keyframe(1, a + Eigen::Vector3d(0.5, 0, 0) + (pair.entry + 1) * up, 1.5),
                                  keyframe(1 + slide_s, a, 0)};
  std::string out;
  write_json(out, j, 0);
  return out + "\n";
}

}  // namespace snapfit::test
