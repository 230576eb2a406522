#pragma once
// The shape with the faces a boolean operation split on one surface (a cylinder cut in
// two arcs) merged back into one, as a CAD system would save it.
#include <ShapeUpgrade_UnifySameDomain.hxx>
#include <TopoDS_Shape.hxx>

namespace snapfit::test {

inline TopoDS_Shape merged_faces(const TopoDS_Shape& shape) {
  ShapeUpgrade_UnifySameDomain unify(shape);
  unify.Build();
  return unify.Shape();
}

}  // namespace snapfit::test
