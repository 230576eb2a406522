#include "io/step_units.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <set>
#include <sstream>

namespace snapfit {
namespace {

// ISO 10303-41's si_prefix names, and $ for none.
const std::set<std::string> kPrefixes = {"$",       ".EXA.",  ".PETA.", ".TERA.",  ".GIGA.",  ".MEGA.", ".KILO.",
                                         ".HECTO.", ".DECA.", ".DECI.", ".CENTI.", ".MILLI.", ".MICRO.", ".NANO.",
                                         ".PICO.",  ".FEMTO.", ".ATTO."};

}  // namespace

std::vector<std::string> step_si_length_units(const std::string& text) {
  std::vector<std::string> units;
  // Entities end with ';' (outside strings; unit entities hold no strings with ';').
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find(';', start);
    if (end == std::string::npos) end = text.size();
    std::string entity = text.substr(start, end - start);
    start = end + 1;
    entity.erase(std::remove_if(entity.begin(), entity.end(), [](unsigned char c) { return std::isspace(c); }),
                 entity.end());
    std::string upper = entity;
    std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
    if (upper.find("LENGTH_UNIT(") == std::string::npos) continue;
    const std::size_t si = upper.find("SI_UNIT(");
    if (si == std::string::npos) continue;
    const std::size_t close = upper.find(')', si);
    if (close == std::string::npos) continue;
    units.push_back(entity.substr(si, close - si + 1));
  }
  return units;
}

std::string step_length_unit_problem(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream all;
  all << in.rdbuf();
  for (const std::string& unit : step_si_length_units(all.str())) {
    std::string upper = unit;
    std::transform(upper.begin(), upper.end(), upper.begin(), [](unsigned char c) { return std::toupper(c); });
    const std::string args = upper.substr(8, upper.size() - 9);  // within SI_UNIT( ... )
    const std::size_t comma = args.find(',');
    const std::string prefix = comma == std::string::npos ? "" : args.substr(0, comma);
    const std::string name = comma == std::string::npos ? args : args.substr(comma + 1);
    if (name != ".METRE.")
      return "unknown length unit " + unit + ": a STEP file's SI length unit is .METRE. with a prefix (" +
             "OpenCASCADE would read it as some other unit)";
    if (!kPrefixes.count(prefix)) return "unknown prefix in the length unit " + unit;
  }
  return "";
}

}  // namespace snapfit
