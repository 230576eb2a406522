// CAD file names (io/cad_format.h).
#include "io/cad_format.h"

#include <cctype>
#include <filesystem>

namespace snapfit {

CadFormat cad_format(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (ext == ".step" || ext == ".stp") return CadFormat::step;
  if (ext == ".iges" || ext == ".igs") return CadFormat::iges;
  return CadFormat::none;
}

bool is_cad_file(const std::string& path) { return cad_format(path) != CadFormat::none; }

}  // namespace snapfit
