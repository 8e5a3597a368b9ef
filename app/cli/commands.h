// Subcommands of the `hdrfusion` tool. Each registers its options on the parent app.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace hdrf::cli {

struct Command {
  CLI::App* app;            // the subcommand, to ask whether it was chosen
  std::function<int()> run;  // runs it; returns the exit status
};

Command AddInfoCommand(CLI::App& app);
Command AddRadianceCommand(CLI::App& app);
Command AddSimulateCommand(CLI::App& app);
Command AddBenchCommand(CLI::App& app);
Command AddCalibrateCommand(CLI::App& app);
Command AddMergeCommand(CLI::App& app);
Command AddScanCommand(CLI::App& app);
Command AddEvalCommand(CLI::App& app);

}  // namespace hdrf::cli
