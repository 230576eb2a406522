#include "cli/parse_options.h"

#include "snapfit/error.h"

namespace snapfit::cli {

Interpolation parse_interpolation(const std::string& name, const std::string& option) {
  if (name == "trilinear") return Interpolation::trilinear;
  if (name == "tricubic") return Interpolation::tricubic;
  throw Error(option + ": expected trilinear or tricubic (got '" + name + "')");
}

}  // namespace snapfit::cli
