#pragma once
// What a CAD import did: the file's solids and units, the solid it tessellated, the
// deflections it used and what came out. `snapfit mesh-info` and `scene-check` print it,
// a run's summary.json holds it.
#include <cstddef>
#include <string>
#include <vector>

#include "snapfit/inspect.h"

namespace snapfit {

// The JSON object back into facts (the import child's reply); throws snapfit::Error
// for text that is not such an object.
CadFacts cad_facts_from_json(const std::string& json_text);

}  // namespace snapfit
