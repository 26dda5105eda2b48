// The study drivers' command lines (tests/bench) on CLI11: each driver declares its options on a CLI::App, each
// value checked where it is declared; parse_args() reads argv into them.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>

namespace polyfloe::tsupport {

// Reads the command line into `app`'s options. Returns the exit code where the driver should stop: 0 after
// printing the usage for --help, 2 for an unknown option or a value an option cannot take (the reason and the
// usage on stderr); nothing where it should go on.
inline std::optional<int> parse_args(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) {  // --help
      std::printf("%s", app.help().c_str());
      return 0;
    }
    std::fprintf(stderr, "%s: %s\n%s", app.get_name().c_str(), e.what(), app.help().c_str());
    return 2;
  }
}

}  // namespace polyfloe::tsupport
