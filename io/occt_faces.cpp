// The analytic faces of a B-rep solid (io/occt_shapes.h): each face's surface classified
// through BRepAdaptor_Surface, for the VPS - constraint hybrid's voxel data expansion
// (seed 002 5.2: the voxels carry the B-rep face they lie on).
#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax1.hxx>
#include <gp_Circ.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Torus.hxx>
#include <cmath>
#include <optional>

#include "io/occt_shapes.h"

namespace snapfit::occt {
namespace {

Eigen::Vector3d vec(const gp_XYZ& p) { return {p.X(), p.Y(), p.Z()}; }

// A wire whose edges all lie on one circle: its centre and radius (mm).
std::optional<ExcludedDisc> circle_of(const TopoDS_Wire& wire) {
  std::optional<ExcludedDisc> out;
  for (TopExp_Explorer ex(wire, TopAbs_EDGE); ex.More(); ex.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(ex.Current());
    if (BRep_Tool::Degenerated(edge)) continue;
    const BRepAdaptor_Curve curve(edge);
    if (curve.GetType() != GeomAbs_Circle) return std::nullopt;
    const gp_Circ c = curve.Circle();
    const ExcludedDisc disc{vec(c.Location().XYZ()), c.Radius()};
    if (out && ((out->centre - disc.centre).norm() > 1e-7 * (1 + disc.radius) ||
                std::abs(out->radius - disc.radius) > 1e-7 * (1 + disc.radius)))
      return std::nullopt;
    out = disc;
  }
  return out;
}

// The outward normal at the middle of the face's parameter range: the surface's normal,
// reversed on a reversed face (as the tessellation rewinds its triangles).
Eigen::Vector3d outward_normal(const TopoDS_Face& face, const BRepAdaptor_Surface& surface, gp_Pnt& at) {
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  gp_Vec du, dv;
  surface.D1(0.5 * (u0 + u1), 0.5 * (v0 + v1), at, du, dv);
  Eigen::Vector3d n = vec(du.Crossed(dv).XYZ());
  if (face.Orientation() == TopAbs_REVERSED) n = -n;
  return n.normalized();
}

// A plane: its outward normal, a point (the centre of its outer circle, or its centroid),
// its box, its outer circle as r_out and its circular inner boundaries as excluded discs.
// An inner boundary that is not a circle is not cut out (the face is then a bound).
AnalyticFace plane_face(const TopoDS_Face& face, const BRepAdaptor_Surface& surface) {
  AnalyticFace f;
  f.kind = FaceKind::plane;
  f.name = "cad plane";
  gp_Pnt at;
  f.axis = outward_normal(face, surface, at);
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props);
  const Eigen::Vector3d centroid = vec(props.CentreOfMass().XYZ());
  const Eigen::Vector3d on_plane = vec(at.XYZ());
  f.origin = centroid - f.axis * (centroid - on_plane).dot(f.axis);
  Bnd_Box box;
  BRepBndLib::AddOptimal(face, box, /*useTriangulation=*/Standard_False, /*useShapeTolerance=*/Standard_False);
  double b[6];
  box.Get(b[0], b[1], b[2], b[3], b[4], b[5]);
  f.lo = Eigen::Vector3d(b[0], b[1], b[2]);
  f.hi = Eigen::Vector3d(b[3], b[4], b[5]);
  const TopoDS_Wire outer = BRepTools::OuterWire(face);
  for (TopExp_Explorer ex(face, TopAbs_WIRE); ex.More(); ex.Next()) {
    const TopoDS_Wire& wire = TopoDS::Wire(ex.Current());
    const std::optional<ExcludedDisc> circle = circle_of(wire);
    if (!circle) continue;
    if (wire.IsSame(outer)) {
      f.origin = circle->centre;
      f.r_out = circle->radius;
    } else {
      f.holes.push_back(*circle);
    }
  }
  return f;
}

// A cylinder or cone: its axis, the profile (a, r) at the ends of the face's v range
// (OpenCASCADE's P(u, v) = C + (R + v sin a)(cos u X + sin u Y) + v cos a Z; a = 0 for a
// cylinder), and which side the material is on: a peg when the outward normal points away
// from the axis.
AnalyticFace revolution_face(const TopoDS_Face& face, const BRepAdaptor_Surface& surface, bool cone) {
  AnalyticFace f;
  f.kind = cone ? FaceKind::cone : FaceKind::cylinder;
  f.name = cone ? "cad cone" : "cad cylinder";
  const gp_Ax1 axis = cone ? surface.Cone().Axis() : surface.Cylinder().Axis();
  const double radius = cone ? surface.Cone().RefRadius() : surface.Cylinder().Radius();
  const double angle = cone ? surface.Cone().SemiAngle() : 0.0;
  f.origin = vec(axis.Location().XYZ());
  f.axis = vec(axis.Direction().XYZ());
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  f.a0 = v0 * std::cos(angle);
  f.r0 = radius + v0 * std::sin(angle);
  f.a1 = v1 * std::cos(angle);
  f.r1 = radius + v1 * std::sin(angle);
  gp_Pnt at;
  const Eigen::Vector3d n = outward_normal(face, surface, at);
  const Eigen::Vector3d rel = vec(at.XYZ()) - f.origin;
  f.material_inside = n.dot(rel - f.axis * rel.dot(f.axis)) > 0;
  return f;
}

// A torus (a fillet, OpenCASCADE's P(u, v) = C + (R + r cos v)(cos u X + sin u Y) +
// r sin v Z): the profile arc over the face's v range about (0, R), when it is at most a
// half turn (mesh/analytic_faces.h's arc is the shorter one); else none.
std::optional<AnalyticFace> torus_face(const TopoDS_Face& face, const BRepAdaptor_Surface& surface) {
  const gp_Torus torus = surface.Torus();
  double u0, u1, v0, v1;
  BRepTools::UVBounds(face, u0, u1, v0, v1);
  constexpr double kPi = 3.14159265358979323846;
  if (!(v1 - v0 < kPi)) return std::nullopt;
  AnalyticFace f;
  f.kind = FaceKind::torus;
  f.name = "cad torus";
  f.origin = vec(torus.Axis().Location().XYZ());
  f.axis = vec(torus.Axis().Direction().XYZ());
  const double big = torus.MajorRadius(), small = torus.MinorRadius();
  f.ac = 0;
  f.rc = big;
  f.a0 = small * std::sin(v0), f.r0 = big + small * std::cos(v0);
  f.a1 = small * std::sin(v1), f.r1 = big + small * std::cos(v1);
  return f;
}

void scale_face(AnalyticFace& f, double s) {
  f.origin *= s;
  f.lo *= s;  // infinities stay infinite (s > 0)
  f.hi *= s;
  f.r_in *= s;
  f.r_out *= s;
  for (ExcludedDisc& hole : f.holes) hole.centre *= s, hole.radius *= s;
  f.a0 *= s, f.a1 *= s, f.r0 *= s, f.r1 *= s, f.ac *= s, f.rc *= s;
}

}  // namespace

SolidFaces analytic_faces_of(const TopoDS_Solid& solid, double scale) {
  SolidFaces out;
  for (TopExp_Explorer ex(solid, TopAbs_FACE); ex.More(); ex.Next()) {
    const TopoDS_Face& face = TopoDS::Face(ex.Current());
    const BRepAdaptor_Surface surface(face);  // with the face's location
    std::optional<AnalyticFace> f;
    switch (surface.GetType()) {
      case GeomAbs_Plane:
        f = plane_face(face, surface);
        break;
      case GeomAbs_Cylinder:
        f = revolution_face(face, surface, false);
        break;
      case GeomAbs_Cone:
        f = revolution_face(face, surface, true);
        break;
      case GeomAbs_Torus:
        f = torus_face(face, surface);  // claims its points, so that they stay unlabelled
        break;
      default:
        break;
    }
    if (!f) {
      ++out.other;  // spheres, splines...: no face; their points take a face nearby, if any
      continue;
    }
    scale_face(*f, scale);
    out.faces.push_back(std::move(*f));
  }
  return out;
}

}  // namespace snapfit::occt
