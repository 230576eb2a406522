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

namespace snapfit {

// One field sampled on every grid point, in grid order (i fastest); a point's
// `components` values are adjacent (x y z for a vector). `values` must hold
// grid.count() * components floats and stay valid during write_vti.
struct GridField {
  std::string name;
  const float* values = nullptr;
  int components = 1;
};

// Writes "<path>.tmp.<pid>" and renames it onto `path`, so readers never see half a
// file. Throws snapfit::Error naming `path` for an empty or malformed grid (a dim < 1,
// spacing not positive, origin not finite), no fields, a field with an empty or
// duplicate name, null values or components outside 1..9, and for I/O failures; no
// file is left behind then. The parent folder must exist.
void write_vti(const std::string& path, const GridSpec& grid, const std::vector<GridField>& fields);

}  // namespace snapfit
