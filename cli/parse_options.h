#pragma once
// Option values shared by several subcommands.
#include <string>

#include "snapfit/query.h"

namespace snapfit::cli {

// "trilinear" or "tricubic"; throws snapfit::Error naming `option` otherwise.
Interpolation parse_interpolation(const std::string& name, const std::string& option = "--interpolation");

}  // namespace snapfit::cli
