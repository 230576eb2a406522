// STEP and IGES parts written by OpenCASCADE (tests/cad_fixtures.h).
#include "tests/cad_fixtures.h"
#include "tests/merged_faces.h"

#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Writer.hxx>
#include <StepBasic_Product.hxx>
#include <StepData_StepModel.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <StepShape_ManifoldSolidBrep.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <UnitsMethods.hxx>
#include <cctype>
#include <filesystem>
#include <map>
#include <optional>
#include <stdexcept>

#include "io/cad_format.h"
#include "io/isolated_import.h"
#include "tests/cad_shape_writer.h"

namespace snapfit::test {
namespace {

double number(const ProceduralPartSpec& spec, const std::string& key, double fallback) {
  const auto it = spec.numbers.find(key);
  return it == spec.numbers.end() ? fallback : it->second;
}

// The defaults of mesh/procedural (docs/scenes.md "Procedural parts").
TopoDS_Shape make_peg(const ProceduralPartSpec& spec) {
  const double r = number(spec, "radius", 5), length = number(spec, "length", 30), c = number(spec, "chamfer", 0);
  const gp_Dir z(0, 0, 1);
  if (c <= 0) return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), z), r, length).Shape();
  const TopoDS_Shape bevel = BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, 0), z), r - c, r, c).Shape();
  const TopoDS_Shape body = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, c), z), r, length - c).Shape();
  return merged_faces(BRepAlgoAPI_Fuse(bevel, body).Shape());
}

TopoDS_Shape make_hole_block(const ProceduralPartSpec& spec) {
  const double r = number(spec, "peg_radius", 5) + number(spec, "clearance", 0);
  const double depth = number(spec, "hole_depth", 20), width = number(spec, "width", 30);
  const double height = number(spec, "height", 30), c = number(spec, "chamfer", 0);
  const gp_Dir z(0, 0, 1);
  const double over = 1;  // the cutting tools reach past the block's faces
  const double bottom = depth >= height ? -height - over : -depth;
  TopoDS_Shape hole = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, bottom), z), r, over - bottom).Shape();
  if (c > 0)  // 45-degree countersink from radius r at z = -c to r + c at z = 0, continued above
    hole = BRepAlgoAPI_Fuse(hole, BRepPrimAPI_MakeCone(gp_Ax2(gp_Pnt(0, 0, -c), z), r, r + c + over, c + over).Shape())
               .Shape();
  const TopoDS_Shape box =
      BRepPrimAPI_MakeBox(gp_Pnt(-width / 2, -width / 2, -height), gp_Pnt(width / 2, width / 2, 0)).Shape();
  return merged_faces(BRepAlgoAPI_Cut(box, hole).Shape());
}

TopoDS_Solid first_solid(const TopoDS_Shape& shape) {
  TopExp_Explorer ex(shape, TopAbs_SOLID);
  if (!ex.More()) throw std::runtime_error("cad fixture: no solid was made");
  return TopoDS::Solid(ex.Current());
}

// Millimetres per unit of the writers' unit names.
double millimetres_per(const std::string& unit) {
  static const std::map<std::string, double> kUnits = {{"MM", 1.0}, {"M", 1000.0}, {"INCH", 25.4}};
  const auto it = kUnits.find(unit);
  if (it == kUnits.end()) throw std::runtime_error("cad fixture: unknown unit " + unit);
  return it->second;
}

// Writes the shape (millimetres) in `unit`; names[i] is the name of the i-th solid the STEP
// writer makes, `product` (when given) the name of every product. For STEP the shape is
// scaled to `unit` here and the writer told it is in that unit: OCCT 7.6's STEP writer
// does not convert millimetres to inches itself (its IGES writer does).
void write_shape_here(const std::string& file, const TopoDS_Shape& mm_shape, const std::string& unit,
                      const std::vector<std::string>& names, const std::optional<std::string>& product) {
  Message::DefaultMessenger()->ChangePrinters().Clear();
  if (cad_format(file) == CadFormat::iges) {
    IGESControl_Controller::Init();
    Interface_Static::SetCVal("xstep.cad.unit", "MM");
    UnitsMethods::SetCasCadeLengthUnit(1.0);
    IGESControl_Writer writer(unit == "INCH" ? "IN" : unit.c_str(), 0);  // faces, as most CAD systems write
    writer.AddShape(mm_shape);
    writer.ComputeModel();
    if (!writer.Write(file.c_str())) throw std::runtime_error("cad fixture: cannot write " + file);
    return;
  }
  gp_Trsf to_unit;
  to_unit.SetScale(gp_Pnt(0, 0, 0), 1.0 / millimetres_per(unit));
  const TopoDS_Shape shape = BRepBuilderAPI_Transform(mm_shape, to_unit, /*copy=*/Standard_True).Shape();
  STEPControl_Writer writer;
  Interface_Static::SetCVal("xstep.cad.unit", unit.c_str());
  UnitsMethods::SetCasCadeLengthUnit(millimetres_per(unit));
  Interface_Static::SetCVal("write.step.unit", unit.c_str());
  if (writer.Transfer(shape, STEPControl_AsIs) != IFSelect_RetDone)
    throw std::runtime_error("cad fixture: cannot transfer the shape for " + file);
  const Handle(StepData_StepModel) model = writer.Model();
  std::size_t next = 0;
  for (Standard_Integer i = 1; i <= model->NbEntities(); ++i) {
    if (const auto p = Handle(StepBasic_Product)::DownCast(model->Value(i)); !p.IsNull() && product)
      p->SetName(new TCollection_HAsciiString(product->c_str()));
    const auto solid = Handle(StepShape_ManifoldSolidBrep)::DownCast(model->Value(i));
    if (solid.IsNull()) continue;
    if (next < names.size()) solid->SetName(new TCollection_HAsciiString(names[next].c_str()));
    ++next;
  }
  if (writer.Write(file.c_str()) != IFSelect_RetDone) throw std::runtime_error("cad fixture: cannot write " + file);
}

// The same in a child process: OCCT's writers keep unit factors in global state that a
// previous write leaves behind (a STEP file written after an IGES file in inches comes out
// scaled), so each write starts from this process's untouched state.
void write_shape(const std::string& file, const TopoDS_Shape& mm_shape, const std::string& unit,
                 const std::vector<std::string>& names, const std::optional<std::string>& product = std::nullopt) {
  const ChildResult r = run_in_child(
      [&] {
        write_shape_here(file, mm_shape, unit, names, product);
        return std::string();
      },
      ChildLimits{2048, 120, 300});
  if (r.status != ChildResult::Status::ok)
    throw std::runtime_error("cad fixture: cannot write " + file + ": " + r.bytes);
}

TopoDS_Solid make_box(const NamedBox& b) {
  return TopoDS::Solid(
      BRepPrimAPI_MakeBox(gp_Pnt(b.min[0], b.min[1], b.min[2]), gp_Pnt(b.max[0], b.max[1], b.max[2])).Shape());
}

}  // namespace

void write_cad_part(const std::string& file, const ProceduralPartSpec& spec, const std::string& unit,
                    const std::string& solid_name) {
  TopoDS_Shape shape;
  if (spec.type == "peg")
    shape = make_peg(spec);
  else if (spec.type == "hole_block")
    shape = make_hole_block(spec);
  else
    throw std::runtime_error("cad fixture: no B-rep for procedural type '" + spec.type + "'");
  write_shape(file, first_solid(shape), unit, {solid_name});
}

void write_cad_shape(const std::string& file, const TopoDS_Shape& mm_shape, const std::string& solid_name) {
  write_shape(file, first_solid(mm_shape), "MM", {solid_name});
}

void write_cad_boxes(const std::string& file, const std::vector<NamedBox>& boxes, const std::string& product) {
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  std::vector<std::string> names;
  for (const NamedBox& b : boxes) {
    builder.Add(compound, make_box(b));
    names.push_back(b.name);
  }
  write_shape(file, compound, "MM", names, product);
}

void write_cad_instances(const std::string& file, const NamedBox& box, double shift) {
  const TopoDS_Solid solid = make_box(box);
  gp_Trsf move;
  move.SetTranslation(gp_Vec(shift, 0, 0));
  BRep_Builder builder;
  TopoDS_Compound compound;
  builder.MakeCompound(compound);
  builder.Add(compound, solid);
  builder.Add(compound, solid.Moved(TopLoc_Location(move)));
  write_shape(file, compound, "MM", {}, box.name);
}

}  // namespace snapfit::test
