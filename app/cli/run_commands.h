// The subcommand plumbing `hdrfusion` and `hdrfusion-experiments` share: each subcommand
// registers its options and returns how to run it; Run parses, runs the chosen one, and
// turns errors into one line on stderr and an exit status (1: a named error, 2: unexpected).
#pragma once

#include <CLI/CLI.hpp>
#include <cctype>
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

// Throws SettingError for a flag given "nan" or "inf": CLI11 reads them as numbers, and a
// range check passes NaN (no comparison with it is true), so `--autosave nan` was taken. No
// flag of these programs means anything by a number that is not finite.
inline void RefuseNonFiniteNumbers(const CLI::App& app) {
  for (const CLI::App* sub : app.get_subcommands()) RefuseNonFiniteNumbers(*sub);
  for (const CLI::Option* o : app.get_options()) {
    if (o->get_lnames().empty() && o->get_snames().empty()) continue;  // positional: a path may be called "inf"
    for (const std::string& v : o->results()) {
      std::string low;
      for (char c : v) low += char(std::tolower(static_cast<unsigned char>(c)));
      if (!low.empty() && (low[0] == '+' || low[0] == '-')) low.erase(0, 1);
      if (low == "nan" || low == "inf" || low == "infinity")
        throw SettingError(o->get_name(), "'" + v + "' is not a finite number");
    }
  }
}

inline int Run(CLI::App& app, const std::vector<Command>& commands, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  }
  const std::string name = app.get_name();
  try {
    RefuseNonFiniteNumbers(app);
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
