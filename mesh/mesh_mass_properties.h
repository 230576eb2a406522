#pragma once
// Volume integrals of a closed, outward-oriented triangle mesh by the divergence theorem.
#include <Eigen/Core>

#include "mesh/mesh.h"

namespace snapfit {

struct SolidMoments {
  double volume = 0;              // signed: < 0 for inward normals
  double mean_square_radius = 0;  // <|q - origin|^2> over the solid
};

// int_V |q|^2 dV = (1/5) sum_T (q.n) int_T |q|^2 dA, exact per triangle:
// int_T |q|^2 dA = (A/6)(|a|^2 + |b|^2 + |c|^2 + a.b + b.c + c.a). Throws snapfit::Error
// for an empty mesh or a zero volume.
SolidMoments solid_moments(const Mesh& mesh, const Eigen::Vector3d& origin = Eigen::Vector3d::Zero());

}  // namespace snapfit
