#pragma once
// Option values shared by several subcommands.
#include <CLI/CLI.hpp>
#include <string>
#include <utility>
#include <vector>

#include "snapfit/query.h"

namespace snapfit::cli {

// "trilinear" or "tricubic"; throws snapfit::Error naming `option` otherwise.
Interpolation parse_interpolation(const std::string& name, const std::string& option = "--interpolation");

// What --strategy takes: "auto", then every strategy's name (include/snapfit/query.h).
std::vector<std::string> strategy_choices();

// "z=12.5" -> ('z', 12.5): a slice along an axis; throws snapfit::Error naming --slice otherwise.
std::pair<char, double> parse_slice(const std::string& text);

// A number option's check: "--step-deg: must be > 0, got 0" (CLI11's PositiveNumber
// prints the range up to the largest double instead).
CLI::Validator positive_number();

// Makes the output folder `dir` and checks that a file can be written in it, before any
// work starts; throws snapfit::Error naming `option` and the folder otherwise.
void check_output_folder(const std::string& dir, const std::string& option = "--out");

}  // namespace snapfit::cli
