#pragma once
// What a CAD import did: the file's solids and units, the solid it tessellated, the
// deflections it used and what came out. `snapfit mesh-info` and `scene-check` print it,
// a run's summary.json holds it.
#include <cstddef>
#include <string>
#include <vector>

namespace snapfit {

struct CadFacts {
  std::string format;               // "STEP" or "IGES"
  std::string file_unit;            // the length unit the file declares, as it spells it
  std::vector<std::string> solids;  // every solid in the file, by the names a part may give
  std::string solid;                // the one tessellated
  std::size_t faces = 0;            // B-rep faces of that solid
  // Of those, the analytic faces the VPS - constraint hybrid reads (mesh/analytic_faces.h:
  // tori only keep their points unlabelled), and the faces on other surfaces (spheres,
  // B-splines), which give none.
  std::size_t planes = 0, cylinders = 0, cones = 0, tori = 0, other_faces = 0;
  double linear_deflection = 0;     // used, in output units: largest distance of the mesh from the surface
  double angular_deflection_deg = 0;
  std::string deflection_source;  // where linear_deflection came from, e.g. "0.025 x grid spacing 0.6"
  std::size_t triangles = 0;      // produced
  double exact_volume = 0;        // of the B-rep solid (OpenCASCADE's integration), output units^3
  double exact_area = 0;          // of its faces, output units^2
};

// Multi-line text (one "cad ...: value" line per fact) and one JSON object.
std::string format_cad_facts(const CadFacts& facts);
std::string cad_facts_json(const CadFacts& facts);

// The JSON object back into facts (the import child's reply); throws snapfit::Error
// for text that is not such an object.
CadFacts cad_facts_from_json(const std::string& json_text);

}  // namespace snapfit
