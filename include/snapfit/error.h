#pragma once
// The one exception type snapfit throws for bad input and failed operations.
// Messages name the thing that failed (file, field, device) and the problem, so the
// CLI can print them as a one-line reason and exit non-zero.
#include <stdexcept>
#include <string>

namespace snapfit {

struct Error : std::runtime_error {
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

}  // namespace snapfit
