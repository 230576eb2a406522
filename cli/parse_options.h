#pragma once
// Option values shared by several subcommands.
#include <string>
#include <utility>

#include "snapfit/query.h"

namespace snapfit::cli {

// "trilinear" or "tricubic"; throws snapfit::Error naming `option` otherwise.
Interpolation parse_interpolation(const std::string& name, const std::string& option = "--interpolation");

// "z=12.5" -> ('z', 12.5): a slice along an axis; throws snapfit::Error naming --slice otherwise.
std::pair<char, double> parse_slice(const std::string& text);

}  // namespace snapfit::cli
