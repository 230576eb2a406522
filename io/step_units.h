#pragma once
// The length units a STEP file declares (ISO 10303-41): each LENGTH_UNIT entity is an SI
// unit, SI_UNIT(prefix, .METRE.), or a conversion-based unit (CONVERSION_BASED_UNIT('INCH',
// ...)) that OpenCASCADE converts itself. OpenCASCADE reads an SI length unit whose name is
// not METRE (say .FURLONG.) without a word, as some other unit: snapfit refuses it instead.
#include <string>
#include <vector>

namespace snapfit {

// The SI_UNIT(...) texts of the file's LENGTH_UNIT entities, as written (spaces removed).
std::vector<std::string> step_si_length_units(const std::string& step_text);

// "" when every SI length unit of the STEP file at `path` is the metre with a known
// prefix; otherwise what is wrong, naming the unit as the file writes it.
std::string step_length_unit_problem(const std::string& path);

}  // namespace snapfit
