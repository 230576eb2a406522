#pragma once
// Grid fields as VTK XML ImageData (.vti), for ParaView and VisIt.
//
// Layout: <VTKFile type="ImageData" version="1.0" byte_order="LittleEndian"
// header_type="UInt64">, WholeExtent "0 nx-1 0 ny-1 0 nz-1", the grid's Origin and
// Spacing, one Float32 DataArray per field in PointData (format="appended"), then
// <AppendedData encoding="raw">_ and per field a UInt64 byte count followed by the raw
// little-endian floats. Each DataArray's offset counts bytes from just after the '_'.
#include <string>
#include <vector>

#include "core/grid.h"
#include "snapfit/export.h"

namespace snapfit {

}  // namespace snapfit
