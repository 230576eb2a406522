#include "cli/parse_options.h"

#include <cmath>
#include <stdexcept>

#include "snapfit/error.h"

namespace snapfit::cli {

Interpolation parse_interpolation(const std::string& name, const std::string& option) {
  if (name == "trilinear") return Interpolation::trilinear;
  if (name == "tricubic") return Interpolation::tricubic;
  throw Error(option + ": expected trilinear or tricubic (got '" + name + "')");
}

std::pair<char, double> parse_slice(const std::string& text) {
  if (text.size() < 3 || text[1] != '=' || std::string("xyz").find(text[0]) == std::string::npos)
    throw Error("--slice: expected x=VALUE, y=VALUE or z=VALUE (got '" + text + "')");
  try {
    std::size_t used = 0;
    const double value = std::stod(text.substr(2), &used);
    if (used != text.size() - 2 || !std::isfinite(value)) throw std::invalid_argument("trailing");
    return {text[0], value};
  } catch (const std::exception&) {
    throw Error("--slice: '" + text.substr(2) + "' is not a number");
  }
}

}  // namespace snapfit::cli
