#pragma once
// Reading progress bars back from what a program printed (core/progress.h writes them as
// plain lines "label: 40% (done/total), ..." where the output is not a terminal).
#include <cctype>
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

// The progress lines in `output` whose count runs past its total ("tuning: 100% (11760/10920)")
// or whose percentage passes 100: a bar must know its total before the work, or grow it.
inline std::vector<std::string> overrun_bars(const std::string& output) {
  std::vector<std::string> bad;
  for (const std::string& line : lines_of(output)) {
    const std::size_t pct = line.find("% (");
    if (pct == std::string::npos) continue;
    const std::size_t slash = line.find('/', pct), close = line.find(')', pct);
    if (slash == std::string::npos || close == std::string::npos || slash > close) continue;
    std::size_t digits = pct;
    while (digits > 0 && std::isdigit(static_cast<unsigned char>(line[digits - 1]))) --digits;
    const long percent = std::atol(line.substr(digits, pct - digits).c_str());
    const double done = std::atof(line.substr(pct + 3, slash - pct - 3).c_str());
    const double total = std::atof(line.substr(slash + 1, close - slash - 1).c_str());
    if (percent > 100 || done > total) bad.push_back(line);
  }
  return bad;
}

}  // namespace snapfit::test
