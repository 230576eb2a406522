#pragma once
// Small helpers shared by the perf/ benchmarks: argument reading, load average, date.
#include <ctime>
#include <fstream>
#include <sstream>
#include <string>

#include "engine/error.h"

namespace snapfit::bench {

// The command line as one string, for the JSON reports.
inline std::string command_line(int argc, char** argv) {
  std::string out;
  for (int i = 0; i < argc; ++i) out += (i ? " " : "") + std::string(argv[i]);
  return out;
}

// True when argument `s` is option `name`, as "--name" or "--name=value".
inline bool is_option(const std::string& s, const std::string& name) {
  return s == name || s.rfind(name + "=", 0) == 0;
}

// The value of option `name` at argv[i]: after '=' or the next argument (advancing i).
inline std::string option_value(int argc, char** argv, int& i, const std::string& name) {
  const std::string s = argv[i];
  const std::string prefix = name + "=";
  if (s.rfind(prefix, 0) == 0) return s.substr(prefix.size());
  if (i + 1 >= argc) throw snapfit::Error(name + ": needs a value");
  return argv[++i];
}

// /proc/loadavg as written, and its 1-minute figure (-1 when unreadable).
inline std::string read_loadavg() {
  std::ifstream f("/proc/loadavg");
  std::string line;
  std::getline(f, line);
  return line;
}
inline double load1() {
  std::istringstream in(read_loadavg());
  double l = -1;
  in >> l;
  return l;
}

inline std::string now_iso() {
  const std::time_t t = std::time(nullptr);
  char buf[64];
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%S%z", std::localtime(&t));
  return buf;
}

}  // namespace snapfit::bench
