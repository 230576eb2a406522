#pragma once
// The library names what a caller asked for by its request member ("SearchRequest::map_fft") or
// scene field, never by a command-line option; the tool says the same in its own terms
// ("--map-fft") wherever it prints the library's text: errors, the jobs' lines, plans.
#include <string>

namespace snapfit::cli {

// `text` with each request member the tool sets from an option replaced by that option.
std::string in_cli_terms(std::string text);

}  // namespace snapfit::cli
