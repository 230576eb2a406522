#pragma once
// Analytic faces (mesh/analytic_faces.h) as bytes, for the CAD import child's reply (one
// program on both ends), and back. A face's name is static text: a decoded face takes the
// name of its kind ("cad plane", "cad cylinder", "cad cone", "cad torus").
#include <string>
#include <string_view>
#include <vector>

#include "mesh/analytic_faces.h"

namespace snapfit {

std::string encode_faces(const std::vector<AnalyticFace>& faces);

// Reads the faces at the start of `bytes` and sets `used` to where they end. Throws an
// Error naming `path` for bytes that do not start with such a list.
std::vector<AnalyticFace> decode_faces(const std::string& path, std::string_view bytes, std::size_t& used);

}  // namespace snapfit
