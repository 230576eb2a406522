// Tessellating a B-rep solid through OpenCASCADE's BRepMesh (io/occt_shapes.h).
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <IMeshTools_Parameters.hxx>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "io/occt_shapes.h"

namespace snapfit::occt {

Tessellation tessellate_solid(const TopoDS_Solid& solid, double deflection_mm, double angle_rad, double scale,
                              const std::string& path) {
  BRepTools::Clean(solid);  // a triangulation the file carried would be kept if it were fine enough
  IMeshTools_Parameters params;
  params.Deflection = deflection_mm;
  params.Angle = angle_rad;
  params.Relative = Standard_False;
  params.InParallel = Standard_False;  // the import child must not start threads
  BRepMesh_IncrementalMesh mesher(solid, params);
  if (!mesher.IsDone()) throw Error(path + ": cannot read CAD file: OpenCASCADE could not tessellate the solid");

  // BRepMesh gives each face its own triangulation; the nodes on a face's boundary come
  // from one discretisation per edge, listed for each face by PolygonOnTriangulation. A
  // boundary node is one mesh vertex for all faces around it: keyed by its B-rep vertex
  // (an edge's end, or any node of a degenerate edge such as a cone's apex) or by its edge
  // and its index along it (a seam's two sides included). Faces sewn from IGES compute the
  // same node from each face's own surface, a little apart; the key joins them anyway.
  Tessellation out;
  std::map<std::pair<const void*, int>, int> vertex_of;  // (vertex or edge TShape, index) -> mesh vertex
  std::vector<int> node_vertex;
  const auto add_vertex = [&](const gp_Pnt& p, std::size_t face) {
    const Eigen::Vector3d q(p.X() * scale, p.Y() * scale, p.Z() * scale);
    if (!q.allFinite())
      throw Error(path + ": cannot read CAD file: face " + std::to_string(face) +
                  " has a non-finite tessellation node");
    out.mesh.vertices.push_back(q);
    return static_cast<int>(out.mesh.vertices.size() - 1);
  };
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& face = TopoDS::Face(ex.Current());
    ++out.faces;
    TopLoc_Location location;
    const Handle(Poly_Triangulation) triangulation = BRep_Tool::Triangulation(face, location);
    if (triangulation.IsNull() || triangulation->NbTriangles() == 0)
      throw Error(path + ": cannot read CAD file: face " + std::to_string(out.faces) +
                  " of the solid could not be tessellated");
    const gp_Trsf placement = location.Transformation();
    const Standard_Integer nodes = triangulation->NbNodes();
    const auto node = [&](Standard_Integer i) { return triangulation->Node(i).Transformed(placement); };
    node_vertex.assign(static_cast<std::size_t>(nodes) + 1, -1);
    for (TopExp_Explorer ee(face, TopAbs_EDGE); ee.More(); ee.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(ee.Current());
      // Looked up by the triangulation and the face's location, which it is stored under.
      const Handle(Poly_PolygonOnTriangulation) polygon =
          BRep_Tool::PolygonOnTriangulation(edge, triangulation, location);
      if (polygon.IsNull()) continue;
      TopoDS_Vertex first, last;
      TopExp::Vertices(edge, first, last);
      const Standard_Integer n = polygon->NbNodes();
      for (Standard_Integer k = 1; k <= n; ++k) {
        const Standard_Integer i = polygon->Node(k);
        if (i < 1 || i > nodes) continue;
        const TopoDS_Vertex* end = BRep_Tool::Degenerated(edge) || k == 1 ? &first : k == n ? &last : nullptr;
        const std::pair<const void*, int> key(
            end && !end->IsNull() ? static_cast<const void*>(end->TShape().get()) : edge.TShape().get(),
            end && !end->IsNull() ? 0 : k);
        const auto [it, added] = vertex_of.emplace(key, -1);
        if (added) it->second = add_vertex(node(i), out.faces);
        node_vertex[i] = it->second;
      }
    }
    for (Standard_Integer i = 1; i <= nodes; ++i)
      if (node_vertex[i] < 0) node_vertex[i] = add_vertex(node(i), out.faces);  // inside the face

    // A reversed face's surface normal points into the solid: its triangles are rewound.
    const bool reversed = face.Orientation() == TopAbs_REVERSED;
    for (Standard_Integer t = 1; t <= triangulation->NbTriangles(); ++t) {
      Standard_Integer a, b, c;
      triangulation->Triangle(t).Get(a, b, c);
      if (std::min({a, b, c}) < 1 || std::max({a, b, c}) > nodes)
        throw Error(path + ": cannot read CAD file: face " + std::to_string(out.faces) +
                    " has a triangle with a node index out of range");
      if (reversed) std::swap(b, c);
      const Eigen::Vector3i tri(node_vertex[a], node_vertex[b], node_vertex[c]);
      // Nodes of a degenerate edge (a cone's apex) are one vertex: their slivers have no area.
      if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2]) continue;
      out.mesh.triangles.push_back(tri);
    }
  }
  return out;
}

SolidGeometry solid_geometry(const TopoDS_Solid& solid) {
  SolidGeometry g;
  Bnd_Box box;
  BRepBndLib::AddOptimal(solid, box, /*useTriangulation=*/Standard_False, /*useShapeTolerance=*/Standard_False);
  box.Get(g.box[0], g.box[1], g.box[2], g.box[3], g.box[4], g.box[5]);
  GProp_GProps volume, area;
  BRepGProp::VolumeProperties(solid, volume);
  BRepGProp::SurfaceProperties(solid, area);
  g.volume = volume.Mass();
  g.area = area.Mass();
  return g;
}

}  // namespace snapfit::occt
