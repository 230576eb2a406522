#pragma once
// OpenCASCADE's side of CAD import (io/cad_load.h): reading a STEP or IGES file into
// named solids, and tessellating one. Only io/cad_load.cpp and io/occt_*.cpp include this
// header, so OpenCASCADE's types stay out of every other header, the public ones included.
#include <Standard_Failure.hxx>
#include <Standard_OutOfMemory.hxx>
#include <TopoDS_Solid.hxx>
#include <cstddef>
#include <new>
#include <string>
#include <vector>

#include "mesh/analytic_faces.h"
#include "mesh/mesh.h"
#include "snapfit/error.h"

namespace snapfit::occt {

struct NamedSolid {
  std::string name;  // unique within the file
  TopoDS_Solid solid;
};

struct CadFile {
  std::string format;                // "STEP" or "IGES"
  std::string file_unit;             // the length unit the file declares, as it spells it
  std::vector<NamedSolid> solids;    // in millimetres (OpenCASCADE converts the file's unit)
  std::size_t sewn_open_shells = 0;  // shells of loose faces that did not close into a solid
};

// Reads `path` (STEP or IGES, by its extension). Throws snapfit::Error naming the file
// when it cannot be read or holds no closed solid.
CadFile read_cad_file(const std::string& path);

struct Tessellation {
  Mesh mesh;              // millimetres times `scale`
  std::size_t faces = 0;  // B-rep faces tessellated
};

// BRepMesh of `solid` at `deflection_mm` and `angle_rad` in this thread; the faces'
// meshes are joined at their shared boundary nodes and each coordinate is multiplied by
// `scale`. Throws snapfit::Error naming `path` when a face cannot be tessellated.
Tessellation tessellate_solid(const TopoDS_Solid& solid, double deflection_mm, double angle_rad, double scale,
                              const std::string& path);

// The solid's analytic faces (mesh/analytic_faces.h), each B-rep face classified by its
// surface (BRepAdaptor_Surface, with the face's location): planes (outward normal from the
// face's orientation; box, outer circle and circular holes), cylinders and cones (axis,
// profile over the face's range, peg or hole from the orientation), and tori (fillets:
// their points stay unlabelled). Faces on other surfaces (spheres, B-splines) give none
// and are counted in `other`. Millimetres times `scale`, as the tessellation.
struct SolidFaces {
  std::vector<AnalyticFace> faces;
  std::size_t other = 0;
};
SolidFaces analytic_faces_of(const TopoDS_Solid& solid, double scale);

// The solid's axis-aligned box (min x, y, z, max x, y, z), volume and surface area from
// its exact geometry, in millimetres.
struct SolidGeometry {
  double box[6] = {};
  double volume = 0;
  double area = 0;
};
SolidGeometry solid_geometry(const TopoDS_Solid& solid);

// Runs `f`, turning OpenCASCADE's exceptions into snapfit::Error naming `path` (and
// Standard_OutOfMemory into std::bad_alloc, which the import child reports as its memory
// limit).
template <class F>
auto guard_occt(const std::string& path, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Standard_OutOfMemory&) {
    throw std::bad_alloc();
  } catch (const Standard_Failure& e) {
    const char* message = e.GetMessageString();
    throw Error(path + ": cannot read CAD file: OpenCASCADE failed (" + e.DynamicType()->Name() +
                (message && *message ? std::string(": ") + message : std::string()) + ")");
  }
}

}  // namespace snapfit::occt
