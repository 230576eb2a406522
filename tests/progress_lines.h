#pragma once
// Reading progress bars back from what a program printed (core/progress.h writes them as
// plain lines "label: 40% (done/total), ..." where the output is not a terminal).
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

namespace snapfit::test {

inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

inline bool starts_with(const std::string& s, const std::string& head) { return s.rfind(head, 0) == 0; }

// The percentage of a plain line "label: 40% (...)"; -1 when it is not one of `label`.
inline int percent_of(const std::string& line, const std::string& label) {
  const std::string head = label + ": ";
  if (!starts_with(line, head)) return -1;
  const std::size_t pct = line.find('%');
  if (pct == std::string::npos) return -1;
  return std::atoi(line.substr(head.size(), pct - head.size()).c_str());
}

}  // namespace snapfit::test
