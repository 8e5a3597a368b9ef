// The subcommand plumbing `hdrfusion` and `hdrfusion-experiments` share: each subcommand
// registers its options and returns how to run it; Run parses, runs the chosen one, and
// turns errors into one line on stderr and an exit status (1: a named error, 2: unexpected).
#pragma once

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "common/error.h"

namespace hdrf::cli {

struct Command {
  CLI::App* app;             // the subcommand, to ask whether it was chosen
  std::function<int()> run;  // runs it; returns the exit status
};

inline int Run(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  const std::string name = app.get_name();
  try {
    for (const auto& c : commands)
      if (c.app->parsed()) return c.run();
  } catch (const Error& e) {
    std::fprintf(stderr, "%s: error: %s\n", name.c_str(), e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: unexpected error: %s\n", name.c_str(), Printable(e.what()).c_str());
    return 2;
  }
  return 0;
}

}  // namespace hdrf::cli
