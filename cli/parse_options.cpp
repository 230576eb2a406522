#include "cli/parse_options.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "snapfit/error.h"

namespace snapfit::cli {

Interpolation parse_interpolation(const std::string& name, const std::string& option) {
  if (const std::optional<Interpolation> interpolation = interpolation_named(name)) return *interpolation;
  throw Error(option + ": expected trilinear or tricubic (got '" + name + "')");
}

std::vector<std::string> strategy_choices() {
  std::vector<std::string> names = {"auto"};
  for (QueryStrategy s : query_strategies()) names.push_back(strategy_name(s));
  return names;
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

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        double value = 0;
        if (!CLI::detail::lexical_cast(text, value)) return "must be a number, got " + text;
        return value > 0 ? std::string() : "must be > 0, got " + text;
      },
      "> 0", "POSITIVE");
}

void check_output_folder(const std::string& dir, const std::string& option) {
  namespace fs = std::filesystem;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw Error(option + " " + dir + ": cannot make the folder (" + ec.message() + ")");
  if (!fs::is_directory(dir, ec)) throw Error(option + " " + dir + ": not a folder");
  const fs::path probe = fs::path(dir) / ".snapfit-write-check";
  {
    std::ofstream out(probe);
    if (!(out << "snapfit\n") || !out.flush())
      throw Error(option + " " + dir + ": cannot write in the folder (" + std::strerror(errno) + ")");
  }
  fs::remove(probe, ec);
}

}  // namespace snapfit::cli
