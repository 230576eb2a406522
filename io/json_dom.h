#pragma once
// JSON text -> DOM for files people write by hand (scenes): every syntax error keeps its
// line and column, and a key repeated within one object is an error naming its path.
#include <nlohmann/json.hpp>
#include <string>

namespace snapfit {

// Parses `text`; throws snapfit::Error "ORIGIN: invalid JSON at line L, column C: ..." or
// "ORIGIN: a.b: duplicate field".
nlohmann::json parse_json_dom(const std::string& text, const std::string& origin);

}  // namespace snapfit
