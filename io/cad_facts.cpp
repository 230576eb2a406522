// CAD import facts as text and JSON (io/cad_facts.h).
#include "io/cad_facts.h"

#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>

#include "snapfit/error.h"

namespace snapfit {

std::string format_cad_facts(const CadFacts& f) {
  std::ostringstream s;
  s << std::setprecision(9);
  s << "cad format: " << f.format << " (length unit in the file: " << f.file_unit << ")\n";
  s << "cad solids: " << f.solids.size() << " (";
  for (std::size_t i = 0; i < f.solids.size(); ++i) s << (i ? ", " : "") << "'" << f.solids[i] << "'";
  s << ")\n";
  s << "cad solid tessellated: '" << f.solid << "', " << f.faces << " faces\n";
  s << "cad analytic faces: " << f.planes << " planes, " << f.cylinders << " cylinders, " << f.cones << " cones, " << f.tori << " tori; "
    << f.other_faces << " on other surfaces\n";
  s << "cad linear deflection: " << f.linear_deflection << " (" << f.deflection_source << ")\n";
  s << "cad angular deflection: " << f.angular_deflection_deg << " deg\n";
  s << "cad triangles produced: " << f.triangles << "\n";
  s << "cad exact volume: " << f.exact_volume << ", exact surface area: " << f.exact_area << "\n";
  return s.str();
}

std::string cad_facts_json(const CadFacts& f) {
  const nlohmann::json j = {
      {"format", f.format},
      {"file_unit", f.file_unit},
      {"solids", f.solids},
      {"solid", f.solid},
      {"faces", f.faces},
      {"analytic_faces", {{"planes", f.planes}, {"cylinders", f.cylinders}, {"cones", f.cones}, {"tori", f.tori}, {"other", f.other_faces}}},
      {"linear_deflection", f.linear_deflection},
      {"angular_deflection_deg", f.angular_deflection_deg},
      {"deflection_source", f.deflection_source},
      {"triangles", f.triangles},
      {"exact_volume", f.exact_volume},
      {"exact_area", f.exact_area},
  };
  return j.dump();
}

CadFacts cad_facts_from_json(const std::string& text) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    CadFacts f;
    f.format = j.at("format").get<std::string>();
    f.file_unit = j.at("file_unit").get<std::string>();
    f.solids = j.at("solids").get<std::vector<std::string>>();
    f.solid = j.at("solid").get<std::string>();
    f.faces = j.at("faces").get<std::size_t>();
    const nlohmann::json& a = j.at("analytic_faces");
    f.planes = a.at("planes").get<std::size_t>();
    f.cylinders = a.at("cylinders").get<std::size_t>();
    f.cones = a.at("cones").get<std::size_t>();
    f.tori = a.at("tori").get<std::size_t>();
    f.other_faces = a.at("other").get<std::size_t>();
    f.linear_deflection = j.at("linear_deflection").get<double>();
    f.angular_deflection_deg = j.at("angular_deflection_deg").get<double>();
    f.deflection_source = j.at("deflection_source").get<std::string>();
    f.triangles = j.at("triangles").get<std::size_t>();
    f.exact_volume = j.at("exact_volume").get<double>();
    f.exact_area = j.at("exact_area").get<double>();
    return f;
  } catch (const nlohmann::json::exception& e) {
    throw Error(std::string("malformed CAD facts: ") + e.what());
  }
}

}  // namespace snapfit
