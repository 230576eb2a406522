#pragma once
// The error for a file that cannot be read or written: the path, then the problem.
#include <string>

#include "snapfit/error.h"

namespace snapfit {

[[noreturn]] inline void file_error(const std::string& path, const std::string& problem) {
  throw Error(path + ": " + problem);
}

}  // namespace snapfit
