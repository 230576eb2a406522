#pragma once
// A benchmark's command line with CLI11: the options every benchmark takes (--quick,
// --device, --out) beside its own, the checks their values share, and --help from their
// descriptions.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <string>

#include "cli/parse_options.h"

namespace snapfit::bench {

// A value that must not be empty ("--out: must not be empty").
inline CLI::Validator non_empty() {
  return CLI::Validator([](std::string& s) { return s.empty() ? std::string("must not be empty") : std::string(); }, "",
                        "NONEMPTY");
}

// What every benchmark's arguments hold: --quick, --device, --out (the benchmark sets its
// default) and the command line as one string.
struct CommonArgs {
  bool quick = false;
  std::string device, out, command_line;
};

// --quick (the benchmark's small mode, `quick_text`) and --out DIR (not empty; `out` holds
// its default). Every option added after this shows its default in --help.
inline void add_quick_and_out(CLI::App& app, bool& quick, std::string& out,
                              const std::string& quick_text = "small mode: a few points (CI proves it runs)") {
  app.option_defaults()->always_capture_default();
  app.add_flag("--quick", quick, quick_text);
  app.add_option("--out", out, "output folder")->check(non_empty());
}

// --device SPEC, the OpenCL device as `snapfit --device` takes it.
inline void add_device_option(CLI::App& app, std::string& device,
                              const std::string& text =
                                  "OpenCL device: index, P:D, cpu|gpu|accelerator or a name "
                                  "substring (default: $SNAPFIT_DEVICE, else PoCL's CPU device; "
                                  "'basic': PoCL's single-threaded driver, the haptic loop's)") {
  app.add_option("--device", device, text);
}

// The options most benchmarks take: --quick, --out DIR and --device SPEC.
inline void add_common_options(CLI::App& app, bool& quick, std::string& device, std::string& out,
                               const std::string& quick_text = "small mode: a few points (CI proves it runs)") {
  add_quick_and_out(app, quick, out, quick_text);
  add_device_option(app, device);
}

// Parses the command line: --help prints the options and exits 0; a bad command line
// prints why and exits with CLI11's status. With SNAPFIT_PARSE_ONLY=1 a good command line
// exits 0 here, before the benchmark runs (as `snapfit` does).
inline void parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    std::exit(app.exit(e));
  }
  const char* parse_only = std::getenv("SNAPFIT_PARSE_ONLY");
  if (parse_only && std::string(parse_only) == "1") std::exit(0);
}

}  // namespace snapfit::bench
