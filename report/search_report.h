#pragma once
// What `snapfit search` writes (snapfit/search.h): one JSON line per pose found, and
// the folder with best_per_rotation.csv, search.html (a chart of it) and top.jsonl.
#include <nlohmann/json.hpp>
#include <string>

#include "snapfit/search.h"

namespace snapfit {

// The poses found, one JSON object a line, best first (docs/design.md "snapfit search").
std::string search_lines(const SearchResult& result);

// Writes best_per_rotation.csv, search.html and top.jsonl (`lines`) into `dir`
// (created). Throws snapfit::Error naming a file that cannot be written.
void write_search_report(const std::string& dir, const SearchResult& result, const std::string& lines,
                         const std::string& title);

}  // namespace snapfit
