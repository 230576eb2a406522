// Length units of scene and mesh files (declared in snapfit/scene.h).
#include <utility>

#include "snapfit/error.h"
#include "snapfit/scene.h"

namespace snapfit {

double metres_per_unit(const std::string& unit_name) {
  static constexpr std::pair<const char*, double> kUnits[] = {{"um", 1e-6}, {"mm", 1e-3}, {"cm", 1e-2},
                                                              {"m", 1.0},   {"km", 1e3},  {"in", 0.0254}};
  for (const auto& [name, metres] : kUnits)
    if (unit_name == name) return metres;
  throw Error("unknown unit '" + unit_name + "' (expected one of um, mm, cm, m, km, in)");
}

}  // namespace snapfit
