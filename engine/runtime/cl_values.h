#pragma once
// Host values in the OpenCL vector types that kernel arguments take.
#include <Eigen/Core>

#include "engine/runtime/device.h"

namespace snapfit {

// (x, y, z, 0) in single precision.
inline cl_float4 float4_of(const Eigen::Vector3d& v) {
  return cl_float4{{float(v.x()), float(v.y()), float(v.z()), 0.0f}};
}

}  // namespace snapfit
