// STEP and IGES files into named solids through OpenCASCADE (io/occt_shapes.h).
#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Sewing.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <IGESControl_Reader.hxx>
#include <IGESData_GlobalSection.hxx>
#include <IGESData_IGESEntity.hxx>
#include <IGESData_IGESModel.hxx>
#include <Interface_InterfaceModel.hxx>
#include <Interface_Static.hxx>
#include <Message.hxx>
#include <Message_Messenger.hxx>
#include <STEPControl_Reader.hxx>
#include <ShapeFix_Solid.hxx>
#include <StepBasic_Product.hxx>
#include <StepBasic_ProductDefinition.hxx>
#include <StepBasic_ProductDefinitionFormation.hxx>
#include <StepRepr_RepresentationItem.hxx>
#include <TColStd_SequenceOfAsciiString.hxx>
#include <TCollection_HAsciiString.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TransferBRep.hxx>
#include <Transfer_TransientProcess.hxx>
#include <UnitsMethods.hxx>
#include <XSControl_TransferReader.hxx>
#include <XSControl_WorkSession.hxx>
#include <algorithm>
#include <map>
#include <tuple>

#include "io/cad_format.h"
#include "io/occt_shapes.h"

namespace snapfit::occt {
namespace {

[[noreturn]] void cad_read_error(const std::string& path, const std::string& problem) {
  throw Error(path + ": cannot read CAD file: " + problem);
}

std::string text(const Handle(TCollection_HAsciiString) & s) { return s.IsNull() ? std::string() : s->ToCString(); }

const char* status_text(IFSelect_ReturnStatus status) {
  switch (status) {
    case IFSelect_RetVoid:
      return "nothing read";
    case IFSelect_RetDone:
      return "read";
    case IFSelect_RetError:
      return "error";
    case IFSelect_RetFail:
      return "failed";
    case IFSelect_RetStop:
      return "stopped";
  }
  return "unknown status";
}

// The name an entity of the file gives the shape transferred from it: a STEP
// representation item's (a solid's) own name, a STEP product's, an IGES entity's label.
std::string entity_name(const Handle(Standard_Transient) & entity) {
  if (const auto item = Handle(StepRepr_RepresentationItem)::DownCast(entity); !item.IsNull())
    return text(item->Name());
  if (const auto definition = Handle(StepBasic_ProductDefinition)::DownCast(entity); !definition.IsNull()) {
    const Handle(StepBasic_ProductDefinitionFormation) formation = definition->Formation();
    if (formation.IsNull() || formation->OfProduct().IsNull()) return "";
    return text(formation->OfProduct()->Name());
  }
  if (const auto iges = Handle(IGESData_IGESEntity)::DownCast(entity); !iges.IsNull() && iges->HasName())
    return text(iges->NameValue());
  return "";
}

// Every solid of the transferred shape with the name the file gives it: the name of the
// smallest named entity whose result holds it (the solid's own name before its product's,
// the part's product before the assembly's), matched by the solid's geometry whatever its
// placement, so that every instance of a part carries the part's name. Unnamed solids
// are "solid N"; a name that repeats is numbered "name [k]".
std::vector<NamedSolid> name_solids(const TopoDS_Shape& shape, const XSControl_Reader& reader) {
  TopTools_IndexedMapOfShape solids;
  TopExp::MapShapes(shape, TopAbs_SOLID, solids);
  // Solid (its TShape) -> (solids in the named entity's result, rank, name); smallest wins.
  std::map<const void*, std::tuple<int, int, std::string>> best;
  const Handle(Transfer_TransientProcess) process = reader.WS()->TransferReader()->TransientProcess();
  const Handle(Interface_InterfaceModel) model = reader.Model();
  if (!process.IsNull() && !model.IsNull()) {
    for (Standard_Integer i = 1; i <= model->NbEntities(); ++i) {
      const Handle(Standard_Transient) entity = model->Value(i);
      const std::string name = entity_name(entity);
      if (name.empty() || !process->IsBound(entity)) continue;
      const TopoDS_Shape result = TransferBRep::ShapeResult(process, entity);
      if (result.IsNull()) continue;
      TopTools_IndexedMapOfShape held;
      TopExp::MapShapes(result, TopAbs_SOLID, held);
      const int rank = Handle(StepBasic_ProductDefinition)::DownCast(entity).IsNull() ? 0 : 1;
      for (Standard_Integer k = 1; k <= held.Extent(); ++k) {
        const auto candidate = std::make_tuple(held.Extent(), rank, name);
        const auto [it, added] = best.emplace(held(k).TShape().get(), candidate);
        if (!added && candidate < it->second) it->second = candidate;
      }
    }
  }
  std::vector<NamedSolid> out;
  std::map<std::string, int> uses;
  for (Standard_Integer i = 1; i <= solids.Extent(); ++i) {
    const auto it = best.find(solids(i).TShape().get());
    std::string name = it != best.end() ? std::get<2>(it->second) : "solid " + std::to_string(i);
    ++uses[name];
    out.push_back({name, TopoDS::Solid(solids(i))});
  }
  std::map<std::string, int> seen;
  for (NamedSolid& s : out)
    if (uses[s.name] > 1) s.name += " [" + std::to_string(++seen[s.name]) + "]";
  return out;
}

// Faces that belong to no solid (IGES files, STEP surface models) sewn into shells; each
// closed shell becomes a solid with outward normals.
std::vector<NamedSolid> sew_loose_faces(const TopoDS_Shape& shape, std::size_t& open_shells) {
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  if (faces.IsEmpty()) return {};
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  // The file's own gaps (its edges' tolerances), at least 1e-6 of the part's size.
  const double tolerance = std::max(1e-6 * std::sqrt(box.SquareExtent()), BRep_Tool::MaxTolerance(shape, TopAbs_EDGE));
  BRepBuilderAPI_Sewing sewing(tolerance);
  for (Standard_Integer i = 1; i <= faces.Extent(); ++i) sewing.Add(faces(i));
  sewing.Perform();
  TopTools_IndexedMapOfShape shells;
  TopExp::MapShapes(sewing.SewedShape(), TopAbs_SHELL, shells);
  std::vector<NamedSolid> out;
  open_shells = 0;
  for (Standard_Integer i = 1; i <= shells.Extent(); ++i) {
    const TopoDS_Shell& shell = TopoDS::Shell(shells(i));
    if (!BRep_Tool::IsClosed(shell)) {
      ++open_shells;
      continue;
    }
    ShapeFix_Solid fix;
    out.push_back({"solid " + std::to_string(out.size() + 1), fix.SolidFromShell(shell)});
  }
  if (out.empty())
    throw Error("holds no closed solid: its " + std::to_string(faces.Extent()) + " faces sew into " +
                std::to_string(open_shells) + " open shell(s)");
  return out;
}

}  // namespace

CadFile read_cad_file(const std::string& path) {
  // OpenCASCADE reports on stdout by default; a query's output must stay JSON.
  Message::DefaultMessenger()->ChangePrinters().Clear();
  CadFile file;
  const bool step = cad_format(path) == CadFormat::step;
  file.format = step ? "STEP" : "IGES";
  STEPControl_Reader step_reader;
  IGESControl_Reader iges_reader;
  XSControl_Reader& reader = step ? static_cast<XSControl_Reader&>(step_reader) : iges_reader;
  // Shapes in millimetres whatever an earlier reader or writer in this process set.
  Interface_Static::SetCVal("xstep.cad.unit", "MM");
  UnitsMethods::SetCasCadeLengthUnit(1.0);
  const IFSelect_ReturnStatus status = reader.ReadFile(path.c_str());
  if (status != IFSelect_RetDone)
    cad_read_error(path, "not a readable " + file.format + " file (OpenCASCADE's reader: " + status_text(status) + ")");
  if (step) {
    TColStd_SequenceOfAsciiString lengths, angles, solid_angles;
    step_reader.FileUnits(lengths, angles, solid_angles);
    for (Standard_Integer i = 1; i <= lengths.Length(); ++i) {
      const std::string unit = lengths(i).ToCString();
      if (file.file_unit.find(unit) == std::string::npos) file.file_unit += (file.file_unit.empty() ? "" : ", ") + unit;
    }
  } else if (const Handle(IGESData_IGESModel) model = iges_reader.IGESModel(); !model.IsNull()) {
    file.file_unit = text(model->GlobalSection().UnitName());
  }
  if (file.file_unit.empty()) file.file_unit = "none declared, millimetre assumed";
  if (reader.NbRootsForTransfer() == 0)
    cad_read_error(path, "holds no shape to transfer (a truncated or empty " + file.format + " file?)");
  reader.TransferRoots();
  if (reader.NbShapes() == 0)
    cad_read_error(path, "none of its shapes could be transferred (a truncated or malformed file?)");
  const TopoDS_Shape shape = reader.OneShape();
  file.solids = name_solids(shape, reader);
  if (file.solids.empty()) {
    try {
      file.solids = sew_loose_faces(shape, file.sewn_open_shells);
    } catch (const Error& e) {
      cad_read_error(path, e.what());
    }
  }
  if (file.solids.empty()) cad_read_error(path, "holds no solid and no faces");
  return file;
}

}  // namespace snapfit::occt
